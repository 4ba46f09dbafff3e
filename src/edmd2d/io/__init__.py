"""Files: GSD trajectories (:mod:`edmd2d.io.gsd`, the HOOMD schema read by OVITO,
freud and HOOMD-blue; through the ``gsd`` package, a dependency) and the
event stream in a CSV file (:mod:`edmd2d.io.events`).
Checkpoints for exact restarts are in :mod:`edmd2d.checkpoint`."""
