"""thaw: melting hollow ice (a two-phase Stefan problem) simulated, meshed and ray-traced.

The Python face of the ``thaw`` command line: the same parsers, rules and libraries, the same
results (bit for bit), without files in between::

    import thaw
    sc = thaw.Scenario.default().with_(**{"water.initial_temperature_c": 4.0})
    r = thaw.simulate(sc)
    r.interfaces["outer_radius_m"]        # NumPy arrays, one per column of interfaces.csv
    r.events                              # [{"kind": "melt_onset", "time_s": ..., ...}, ...]
    T = r.fields(10)["temperature_c"]     # a read-only view of the solver's memory (no copy)
    V, F = thaw.mesh(r, 10)               # the ice | air surface at step 10
    img = thaw.render("data/scenes/s1_ice_shell.toml", width=320, height=320)
    thaw.run(sc, "out", frames="0-3", progress=print)

Bad input raises :class:`thaw.UserError` (``.file``, ``.key``, ``.problem``; its text is the
command line's), a failure inside thaw :class:`thaw.InternalError`. Long calls release the GIL
and stop on Ctrl-C with KeyboardInterrupt within a second. Guide: docs/python.md.
"""
import json as _json
import os as _os
import tomllib as _tomllib

from . import _toml
from ._errors import InternalError, UserError
from . import _thaw

__version__ = _thaw.__version__
Result = _thaw.Result

__all__ = ["Scenario", "Result", "simulate", "mesh", "render", "run", "UserError",
           "InternalError", "__version__"]


class Scenario:
    """A thaw scenario: one TOML document, as ``thaw simulate`` and ``thaw run`` read it.

    Make one with :meth:`load`, :meth:`default` or :meth:`from_dict`; derive variants with
    :meth:`with_`. A Scenario is immutable and checked when made: the simulation's sections
    ([simulation], [shell], [shape], [water], [ice], [inner_boundary], [outer_boundary],
    [materials]) by the parser and rules of ``thaw simulate``, so a bad key or value raises
    :class:`thaw.UserError` at once with the command line's message. The sections of ``thaw run``
    ([film], [mesh], [render]) are checked by :func:`thaw.run`, as ``thaw simulate`` leaves them
    to ``thaw run``.

    Attributes:
        text: the TOML document (what ``thaw run`` copies to DIR/scenario.toml).
        source: the name messages use for it (a file name, or what made it).
    """

    __slots__ = ("text", "source", "_sim", "_builtin")

    def __init__(self, *args, **kwargs):
        raise TypeError("use thaw.Scenario.load(path), .default() or .from_dict(d)")

    @classmethod
    def _make(cls, sim, text, source, builtin=False):
        self = object.__new__(cls)
        object.__setattr__(self, "_sim", sim)
        object.__setattr__(self, "text", text)
        object.__setattr__(self, "source", source)
        object.__setattr__(self, "_builtin", builtin)
        return self

    def __setattr__(self, name, value):
        raise AttributeError("a Scenario is immutable; use scenario.with_(...)")

    @classmethod
    def load(cls, path):
        """The scenario file at ``path`` (TOML), parsed as ``thaw simulate path`` parses it.

        Raises :class:`thaw.UserError` for a missing or malformed file, an unknown key or a
        value out of range, with the command line's text.
        """
        path = _os.fspath(path)
        sim, text = _thaw.load_scenario(path)
        return cls._make(sim, text, path)

    @classmethod
    def default(cls):
        """The built-in default scenario (data/scenarios/default.toml): a hollow ice sphere,
        2 cm core of 10 C water, 3 cm outer radius, ice at -5 C, in a 25 C air stream."""
        sim, text = _thaw.default_scenario()
        return cls._make(sim, text, sim.source_name, builtin=True)

    @classmethod
    def from_dict(cls, d, source="<dict>"):
        """A scenario from a nested dict keyed as the TOML file is, e.g.
        ``{"simulation": {"duration_s": 600.0}, "water": {"initial_temperature_c": 4.0}}``.

        Keys left out take the defaults the file format documents (docs/simulate.md). The dict
        is written as TOML (see :attr:`text`) and parsed by thaw's parser, so the rules are the
        file's and messages name ``source`` and the line of that text.
        """
        text = _toml.dumps(d)
        return cls._make(_thaw.parse_scenario(text, source), text, source)

    @classmethod
    def from_toml(cls, text, source="<text>"):
        """A scenario from TOML text."""
        return cls._make(_thaw.parse_scenario(text, source), text, source)

    def to_dict(self):
        """The document as a nested dict (as written: keys left out are not filled in; see
        :attr:`parameters` for every effective value)."""
        return _tomllib.loads(self.text)

    @property
    def parameters(self):
        """Every effective parameter of the simulation, keyed as in the file (summary.json's
        "parameters")."""
        return _json.loads(self._sim.parameters_json())

    @property
    def output_times(self):
        """The output times [s] of :func:`thaw.simulate`: 0, interval, ..., duration_s."""
        return self._sim.output_times()

    def with_(self, **changes):
        """A copy with the dotted keys changed, for sweeps::

            sc.with_(**{"water.initial_temperature_c": 4.0, "simulation.duration_s": 900.0})

        Each key names a value of the document ("section.key", "render.image.width"); missing
        tables are made. The new document is parsed and checked as a file would be: a misspelt
        key raises :class:`thaw.UserError` ("unknown key"), never falls back to a default.
        """
        doc = self.to_dict()
        for dotted, value in changes.items():
            if not _toml.set_dotted(doc, dotted, value):
                raise UserError(f"{dotted}: not a table on the way to this key", "", dotted,
                                "not a table on the way to this key")
        source = self.source if self.source.endswith("(edited)") else f"{self.source} (edited)"
        text = _toml.dumps(doc)
        return Scenario._make(_thaw.parse_scenario(text, source), text, source)

    def __repr__(self):
        return f"thaw.Scenario(source={self.source!r})"


def simulate(scenario, progress=None):
    """Runs the scenario's simulation, as ``thaw simulate`` does, and returns a :class:`Result`.

    Args:
        scenario: a :class:`thaw.Scenario` (or a path to a scenario file).
        progress: optional ``progress(stage, done, total)``, called on this thread with the
            output times reached.

    Returns a :class:`thaw.Result`:
        ``interfaces``: dict of NumPy arrays, the columns of interfaces.csv (bit for bit the
        values the command line writes); ``events``: list of dicts (kind, time_s, radius_m);
        ``summary``: summary.json as a dict; ``fields(step)``: the solver's fields at an output
        step as read-only NumPy views (no copy); ``write(dir)``: the result folder of
        ``thaw simulate --out dir``.

    Releases the GIL while it runs; Ctrl-C raises KeyboardInterrupt within a second, and the
    next call works. Raises :class:`thaw.UserError` on a scenario the solver's rules refuse.
    """
    if not isinstance(scenario, Scenario):
        scenario = Scenario.load(scenario)
    return _thaw.simulate(scenario._sim, progress)


def _summary(self):
    """summary.json as a dict: every effective parameter, the events, solver statistics."""
    return _json.loads(self.summary_json())


Result.summary = property(_summary)


def mesh(result, step, surface="outer", jobs=0):
    """The triangle mesh of one surface of ``result`` at output ``step``, as ``thaw mesh`` makes it.

    Args:
        result: a :class:`thaw.Result`.
        step: the output index (negative counts from the end).
        surface: "outer" (ice | air) or "inner" (water | ice).
        jobs: meshing threads (0 = all cores).

    Returns ``(vertices, triangles)``: float64 #V x 3 positions [m] and int64 #F x 3 zero-based
    vertex indices, counter-clockwise seen from outside. Both are empty when the surface has
    vanished at that step (no ice, no liquid core left).
    """
    return _thaw.mesh(result, step, surface, jobs)


def render(scene, progress=None, **overrides):
    """Renders a scene as ``thaw render`` does and returns the linear image.

    Args:
        scene: a scene file path (TOML, docs/render.md), or a dict keyed as that file
            (relative mesh files are then resolved against the current folder).
        progress: optional ``progress(stage, done, total)`` (tiles done).
        **overrides: the command line's flags: width, height, spp, max_depth, exposure,
            dispersion, dispersion_wavelengths, dispersion_resolution_nm, wavelength_pattern,
            threads; each checked by the rule of the [image] key it overrides.

    Returns a float32 NumPy array of shape (height, width, 3), linear radiance, row 0 at the
    top: the pixels ``thaw render -o image.pfm`` writes (PFM stores them bottom row first).
    """
    if isinstance(scene, dict):
        return _thaw.render_text(_toml.dumps(scene), "<dict>", _os.getcwd(), overrides, progress)
    return _thaw.render_file(_os.fspath(scene), overrides, progress)


def _frames_text(frames):
    if frames is None or isinstance(frames, str):
        return frames
    if isinstance(frames, int):
        return str(frames)
    if isinstance(frames, range):
        if len(frames) == 0 or frames.step < 1:
            raise UserError(f"frames: an empty or reversed range ({frames!r})", "", "frames",
                            f"an empty or reversed range ({frames!r})")
        return f"{frames.start}:{frames[-1]}:{frames.step}"
    raise TypeError(f"frames: a string such as '10-20' or '3:40:2', an int or a range (got {frames!r})")


def run(scenario, out_dir, frames=None, progress=None, *, stage=None, force=False, jobs=0,
        size=None, spp=None, fps=None):
    """Simulates, meshes, renders and films ``scenario`` into ``out_dir``, as ``thaw run`` does.

    Args:
        scenario: a :class:`thaw.Scenario` (its whole document: [film], [mesh] and [render]
            are checked here), or a path to a scenario file.
        out_dir: the output folder (``thaw run --out``); reruns are incremental.
        frames: only these frames: "10-20", "3:40:2", an int or a range (``--frames``).
        progress: optional ``progress(stage, done, total)``, called on this thread.
        stage: run only this stage ("simulate", "mesh", "render", "film", "inspect").
        force: redo every stage.  jobs: worker threads (0 = all cores).
        size: "WIDTHxHEIGHT" or (width, height).  spp: samples per pixel.  fps: film rate.

    Returns a dict: film, gif, plot, pvd, handoff_scene, fields_pvd, handoff_vdb (paths or None),
    events (lines as ``thaw run`` prints them), stages (stage, seconds, skipped, items_done),
    frames, total_seconds.
    """
    if not isinstance(scenario, Scenario):
        scenario = Scenario.load(scenario)
    if isinstance(size, (tuple, list)):
        size = f"{size[0]}x{size[1]}"
    return _thaw.run(scenario._builtin, scenario.text, scenario.source, _os.fspath(out_dir),
                     _frames_text(frames), stage, size, spp, fps, force, jobs, progress)
