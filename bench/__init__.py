"""Benchmarks of bearingsim: assembler scaling, integrators at equal error, steady states.

Run all of them with ``python -m bench.run_all --out docs/benchmarks.md [--quick]``. The
benchmarks only measure and report; nothing here asserts a timing.
"""

import matplotlib

matplotlib.use("Agg")
