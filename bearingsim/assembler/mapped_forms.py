"""The mapped-ball kernels of one assembled model, built on first request per form
(:class:`MappedForms`, what :attr:`System.mapped <bearingsim.assembler.System.mapped>` holds),
and the ODE form of a model with nonlinear blocks built on its mapped DAE form
(:func:`through_newton`). The kernels themselves are built by
:func:`~bearingsim.assembler.mapped.mapped_kernel`.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from bearingsim.assembler.dae import DAE
from bearingsim.assembler.function_options import rootfinder_options
from bearingsim.assembler.ir import Causal, Repeats
from bearingsim.assembler.mapped import MappedKernel, mapped_kernel
from bearingsim.assembler.mapped_parts import NotMappable

__all__ = ["MappedForms", "through_newton"]


def through_newton(dae_kernel: MappedKernel, guess: list[float], rootfinder: str,
                   newton_tol: float) -> MappedKernel:
    """The ODE form ``ode(t, x, u, p)`` of a model with nonlinear blocks from its mapped DAE
    form ``dae(t, x, z, u, p) -> (ode, alg)``: ``z`` from one CasADi rootfinder on ``alg = 0``
    (every ball's Newton block at once; its Jacobian ``d alg / d z`` is the DAE form's
    chain-rule Jacobian, block diagonal over the balls), the right-hand side and the observed
    variables at that ``z``, and the exact Jacobian by the implicit function theorem,
    ``d ode / d a = F_a - F_z G_z^-1 G_a`` for ``a`` in ``t, x, u``, from the same blocks.
    Code size grows with one ball, as the DAE form's does.

    Parameters
    ----------
    dae_kernel : MappedKernel
        The mapped DAE form.
    guess : list of float
        Start of the Newton iteration (the tearing variables' start values, in ``z`` order).
    rootfinder : str
        CasADi rootfinder plugin (``fast_newton`` generates C).
    newton_tol : float
        Absolute tolerance of the residual.

    Returns
    -------
    MappedKernel
        The ODE form.
    """
    F, JF, obs = dae_kernel.function, dae_kernel.jacobian, dae_kernel.observe
    sizes = [F.size1_in(i) for i in range(F.n_in())]  # t, x, z, u, p
    t, x, u, p = (ca.MX.sym(n, sizes[i]) for n, i in (("t", 0), ("x", 1), ("u", 3), ("p", 4)))
    n_ode, n_z = F.size1_out(0), sizes[2]
    # alg(z, w) with w = (t, x, u, p), differentiated by calling the chain-rule Jacobian
    # (parameters are not differentiable, as in every kernel)
    z_s, w = ca.MX.sym("z", n_z), ca.MX.sym("w", sizes[0] + sizes[1] + sizes[3] + sizes[4])
    tw, xw, uw, pw = ca.vertsplit(w, list(np.cumsum([0, *sizes[:2], *sizes[3:]])))
    blocks_w = JF(tw, xw, z_s, uw, pw, ca.MX(ca.Sparsity(n_ode, 1)), ca.MX(ca.Sparsity(n_z, 1)))
    jac_g = ca.Function("jac_alg_balls", [z_s, w, ca.MX.sym("out", ca.Sparsity(n_z, 1))],
                        [blocks_w[7], ca.horzcat(blocks_w[5], blocks_w[6], blocks_w[8],
                                                 blocks_w[9])])
    g = ca.Function("alg_balls", [z_s, w], [F(tw, xw, z_s, uw, pw)[1]],
                    {"custom_jacobian": jac_g, "never_inline": True})
    solve = ca.rootfinder("newton_balls", rootfinder, g,
                          rootfinder_options(rootfinder, newton_tol))
    z = solve(ca.DM(guess), ca.vertcat(t, x, u, p))
    args, names = [t, x, u, p], ["t", "x", "u", "p"]
    fn = ca.Function("ode", args, [F(t, x, z, u, p)[0]], names, ["ode"],
                     {"is_diff_in": [True, True, True, False]})
    blocks = JF(t, x, z, u, p, ca.MX(ca.Sparsity(n_ode, 1)), ca.MX(ca.Sparsity(n_z, 1)))
    f_z, g_z = blocks[2], blocks[7]
    jac_outs = []
    for a, (f_a, g_a) in enumerate(zip(blocks[:5], blocks[5:], strict=True)):
        if a == 2:  # z: not an input of the ODE form
            continue
        if a == 4:  # p: not differentiable
            jac_outs.append(ca.MX(ca.Sparsity(n_ode, sizes[4])))
            continue
        jac_outs.append(f_a - ca.mtimes(f_z, ca.solve(g_z, g_a, "qr")))
    out = ca.MX.sym("out_ode", ca.Sparsity(n_ode, 1))
    jac = ca.Function("jac_ode", [*args, out], jac_outs, [*names, "out_ode"],
                      [f"jac_ode_{n}" for n in names])
    observe = ca.Function("observe", args, [obs(t, x, z, u, p)], names, ["observe"])
    return MappedKernel(fn, jac, observe, dae_kernel.ball_function)


class MappedForms:
    """The mapped kernels of one assembled model, built on first request per form.

    Parameters
    ----------
    dae, causal, repeats
        What the assembler's passes produced (kept for the lazy build); ``None`` for forms
        restored by :meth:`from_data`.
    rootfinder, newton_tol
        Rootfinder plugin and tolerance of the nonlinear blocks: the ODE form of a model with
        nonlinear blocks solves them (:func:`through_newton`).
    """

    FORMS = ("ode", "dae")

    def __init__(self, dae: DAE | None, causal: Causal | None, repeats: Repeats | None,
                 rootfinder: str = "fast_newton", newton_tol: float = 1e-12):
        self._dae, self._causal, self._repeats = dae, causal, repeats
        self._rootfinder, self._newton_tol = rootfinder, newton_tol
        self._built: dict[str, MappedKernel | NotMappable] = {}
        self.summary = ", ".join(f"{s.name or 'root'}: {s.count} members"
                                 for s in repeats.sets) if repeats is not None else ""
        """The sets, e.g. ``"inner_layer: 13 members, outer_layer: 14 members"`` (a member of a
        row of balls is one ball with its contacts, pocket and drag)."""

    def get(self, form: str) -> MappedKernel:
        """The mapped kernel of ``form`` (``"ode"`` or ``"dae"``).

        Parameters
        ----------
        form : {"ode", "dae"}
            Kernel form.

        Returns
        -------
        MappedKernel
            The kernel (built on first use).

        Raises
        ------
        NotMappable
            When this form cannot be mapped (the message says why).
        """
        found = self._built.get(form)
        if found is None:
            try:
                if self._repeats is None:
                    raise NotMappable(f"the {form} form was not built before packing")
                if form == "ode" and self._causal.nonlinear:
                    guess = [g for blk in self._causal.nonlinear for g in blk.guess]
                    found = through_newton(self.get("dae"), guess, self._rootfinder,
                                           self._newton_tol)
                else:
                    found = mapped_kernel(self._dae, self._causal, self._repeats, form)
            except NotMappable as exc:
                found = exc
            self._built[form] = found
        if isinstance(found, NotMappable):
            raise found
        return found

    def find(self, form: str) -> MappedKernel | None:
        """The mapped kernel of ``form``, or None when it cannot be mapped.

        Parameters
        ----------
        form : {"ode", "dae"}
            Kernel form.

        Returns
        -------
        MappedKernel or None
            The kernel, or None.
        """
        try:
            return self.get(form)
        except NotMappable:
            return None

    def to_data(self) -> dict:
        """Plain data (every form built, functions serialized) for another process.

        Returns
        -------
        dict
            Picklable plain data.
        """
        forms = {}
        for form in self.FORMS:
            try:
                k = self.get(form)
            except NotMappable as exc:
                forms[form] = str(exc)
            else:
                forms[form] = [f.serialize() for f in (k.function, k.jacobian, k.observe,
                                                       k.ball_function)]
        return {"summary": self.summary, "forms": forms}

    @classmethod
    def from_data(cls, data: dict) -> MappedForms:
        """The forms of :meth:`to_data`.

        Parameters
        ----------
        data : dict
            From :meth:`to_data`.

        Returns
        -------
        MappedForms
            The forms.
        """
        out = cls(None, None, None)
        out.summary = data["summary"]
        for form, value in data["forms"].items():
            out._built[form] = (NotMappable(value) if isinstance(value, str) else MappedKernel(
                *[ca.Function.deserialize(v) for v in value]))
        return out
