# A stand-in for ParaView's Python package, for checking data/paraview/open_run.py where ParaView
# is not installed (Debian 12's paraview removes the VTK development packages thaw builds with).
# Only paraview.simple exists, built on VTK's own XML readers: see simple.py.
