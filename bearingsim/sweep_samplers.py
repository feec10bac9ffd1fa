"""The names of the samplers of a sweep (``bearingsim sweep --sampler``), apart from
:mod:`bearingsim.scenes.sampling`, which implements them: the command builds its parser before
it starts the sweep's worker server (:mod:`bearingsim.sweep_server`), and importing any module
of ``bearingsim.scenes`` imports the whole scenes package first (0.4-0.5 s), which the server's
start, and the first sweep's workers, would wait for."""

__all__ = ["SAMPLERS"]

SAMPLERS = ("lhs", "lhs-optimal", "sobol")
"""Names of the samplers :func:`~bearingsim.scenes.sampling.sample_points` takes."""
