"""Files: GSD trajectories (:mod:`edmd2d.io.gsd`, the HOOMD schema read by OVITO,
freud and HOOMD-blue; needs the ``gsd`` package, ``pip install edmd2d[io]``) and the
event stream in a CSV file (:mod:`edmd2d.io.events`).
Checkpoints for exact restarts are in :mod:`edmd2d.checkpoint`."""
