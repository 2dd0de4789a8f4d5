#!/usr/bin/python3
"""Runs a notebook headless, as CTest does for examples/sweep.ipynb: every cell through nbclient
and ipykernel (Debian's python3-nbclient, python3-ipykernel), in the notebook's own folder, with
the kernel's inline Matplotlib backend (no display). Fails on the first cell that raises;
writes the executed notebook (with
its figures) to OUT_DIR for a look.

    run_notebook.py NOTEBOOK.ipynb OUT_DIR
"""
import os
import pathlib
import sys

import nbclient
import nbformat

notebook, out_dir = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
# The kernel's own inline backend (matplotlib-inline) captures the figures without a display; a
# backend named in the environment (Agg) would override it and lose them.
os.environ.pop("MPLBACKEND", None)
nb = nbformat.read(notebook, as_version=4)
client = nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                 resources={"metadata": {"path": str(notebook.parent)}})
client.execute()
out_dir.mkdir(parents=True, exist_ok=True)
nbformat.write(nb, out_dir / notebook.name)
images = sum(1 for c in nb.cells if c.cell_type == "code"
             for o in c.get("outputs", []) if "image/png" in o.get("data", {}))
print(f"{notebook.name}: {len(nb.cells)} cells run, {images} figure(s); executed copy in {out_dir}")
if images == 0:
    sys.exit("no figure was made")
