"""Benchmark: stiffness matrix and natural frequencies of a 7020 duplex pair, exact Jacobian
against finite differences on the same assembled model.

* **exact**: equilibrium (Newton), linearization with CasADi's exact Jacobians, ``K = C^-1`` from
  the static compliance ``-(A^-1 B)``, five frequencies by ``scipy.linalg.eigh``.
* **FD (equilibria)**: the compliance by central differences of the equilibrium displacement
  over +-load steps (ten extra equilibria), as a black-box equilibrium solver would do it.
* **FD (state derivative)**: ``K = -M d(dv/dt)/dq`` by central differences of the compiled
  right-hand side (ten evaluations).

Run alone with ``python -m bench.duplex [--quick]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from bearingsim.studies.duplex import DuplexModel, modal_analysis
from bench.common import fmt, markdown_table

__all__ = ["run", "fd_equilibrium_stiffness", "fd_rhs_stiffness"]

DESIGNATIONS = ("7020C", "7020A5", "7020A")
LEVELS = ("light", "medium", "heavy")
_LOAD_STEPS = (20.0, 20.0, 20.0, 2.0, 2.0)  # N, N m
_Q_STEPS = (1e-8, 1e-8, 1e-8, 1e-7, 1e-7)  # m, rad


def fd_equilibrium_stiffness(model: DuplexModel, **config) -> np.ndarray:
    """K from central differences of the equilibrium displacement over load steps."""
    compliance = np.empty((5, 5))
    for j, (name, h) in enumerate(zip(("Fx", "Fy", "Fz", "Mx", "My"), _LOAD_STEPS,
                                      strict=True)):
        plus = model.equilibrium(loads={name: h}, **config).displacement
        minus = model.equilibrium(loads={name: -h}, **config).displacement
        compliance[:, j] = (plus - minus) / (2 * h)
    return np.linalg.inv(compliance)


def fd_rhs_stiffness(model: DuplexModel, **config) -> np.ndarray:
    """K from central differences of the state derivative at the equilibrium."""
    eq = model.equilibrium(**config)
    system = model.system
    p = system.p0(eq.parameters)
    q_idx = [system.state_names.index(f"shaft.{k}") for k in ("x", "y", "z", "tx", "ty")]
    v_idx = [system.state_names.index(f"shaft.{k}") for k in ("vx", "vy", "vz", "wx", "wy")]
    jac = np.empty((5, 5))
    for j, h in enumerate(_Q_STEPS):
        xp, xm = eq.state.copy(), eq.state.copy()
        xp[q_idx[j]] += h
        xm[q_idx[j]] -= h
        jac[:, j] = (system.rhs(0.0, xp, p=p)[v_idx] - system.rhs(0.0, xm, p=p)[v_idx]) / (2 * h)
    return -model.mass @ jac


def _exact(model: DuplexModel, **config) -> np.ndarray:
    return model.stiffness(model.equilibrium(**config))


def _timed(fn, repeats: int):
    best, out = float("inf"), None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _grid(model: DuplexModel, method) -> list[np.ndarray]:
    freqs = []
    for d in DESIGNATIONS:
        for level in LEVELS:
            k = method(model, preload=level, bearing=d)
            freqs.append(modal_analysis(k, model.mass).frequencies)
    return freqs


def run(quick: bool) -> str:
    """Run the benchmark; return a Markdown section body.

    Parameters
    ----------
    quick : bool
        One repetition instead of three.

    Returns
    -------
    str
    """
    repeats = 1 if quick else 3
    t0 = time.perf_counter()
    model = DuplexModel("7020C", "DF")
    t_asm = time.perf_counter() - t0
    methods = {"exact Jacobian": _exact, "FD (equilibria)": fd_equilibrium_stiffness,
               "FD (state derivative)": fd_rhs_stiffness}
    config = {"preload": "medium"}
    rows, ref_k, ref_f, t_ref, t_ref_grid = [], None, None, None, None
    for name, method in methods.items():
        t_one, k = _timed(lambda method=method: modal_analysis(method(model, **config),
                                                               model.mass), repeats)
        t_grid, freqs = _timed(lambda method=method: _grid(model, method), repeats)
        if ref_k is None:
            ref_k, ref_f, t_ref, t_ref_grid = k.stiffness, np.array(freqs), t_one, t_grid
        k_err = np.max(np.abs(k.stiffness - ref_k)) / np.max(np.abs(ref_k))
        f_err = np.max(np.abs(np.array(freqs) / ref_f - 1.0))
        rows.append([name, f"{t_one * 1e3:.1f}", fmt(t_one / t_ref), f"{t_grid:.2f}",
                     fmt(t_grid / t_ref_grid), fmt(k_err, 2), fmt(f_err, 2)])
    modes = modal_analysis(ref_k, model.mass)
    table = markdown_table(
        ["method", "one config [ms]", "ratio", "3 x 3 study [s]", "ratio",
         "K error (max abs / max K)", "max freq. rel. error"], rows)
    freq_line = ", ".join(f"{n} {f:.0f} Hz" for n, f in zip(modes.names, modes.frequencies,
                                                            strict=True))
    return "\n".join([
        "7020C DF pair on the default shaft (100 mm x 400 mm steel, rows 300 mm apart); one "
        f"assembled system ({t_asm:.1f} s to assemble and compile) serves all nine "
        "configurations (7020C/A5/A x light/medium/heavy): contact angle, Hertz constants and "
        "spacer offset are parameters. Times are the best of "
        f"{repeats} run(s) and include the equilibrium solve.",
        "",
        table,
        "",
        f"Medium preload (1270 N): {freq_line}.",
    ])


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    print(run(parser.parse_args().quick))
