"""One documentation template for every component: what a model declares, rendered from the
model itself (so the documentation cannot drift from the equations' symbols).

:func:`component_reference` renders a component instance as a Markdown section: the class
docstring's summary, the constructor arguments (the class's numpydoc ``Parameters``), then
tables of its model parameters (unit, value, valid range, description), inputs, variables and
connectors (each field with its unit and kind) and its sub-components.
"""

from __future__ import annotations

import inspect
import re
from collections import Counter

from bearingsim.language.component import Component
from bearingsim.language.declarations import Flow, Input, Parameter, Potential, Variable

__all__ = ["component_reference", "constructor_arguments", "documented_arguments"]


def constructor_arguments(cls: type[Component]) -> list[str]:
    """Names of the constructor's arguments a user gives (without ``self`` and ``name``).

    Parameters
    ----------
    cls : type
        A component class.

    Returns
    -------
    list of str
        The argument names, in signature order.
    """
    init = getattr(cls.__init__, "__wrapped__", cls.__init__)
    params = inspect.signature(init).parameters.values()
    return [p.name for p in params if p.name not in ("self", "name")
            and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]


def documented_arguments(cls: type[Component]) -> list[str]:
    """Argument names listed in the numpydoc ``Parameters`` section of the class docstring
    (``a : type`` and ``a, b : type`` lines).

    Parameters
    ----------
    cls : type
        A component class.

    Returns
    -------
    list of str
        The documented names, in docstring order.
    """
    doc = inspect.cleandoc(cls.__doc__ or "")
    match = re.search(r"^Parameters\n-+\n(.*?)(?=^\S[^\n]*\n-+\n|\Z)", doc, re.S | re.M)
    if match is None:
        return []
    names: list[str] = []
    for line in match.group(1).splitlines():
        head = re.match(r"^(\*{0,2}[A-Za-z_][\w, *]*?)\s*:", line)
        if head and not line.startswith(" "):
            names += [n.strip().lstrip("*") for n in head.group(1).split(",")]
    return names


def _range(decl: Parameter | Input) -> str:
    low, high = getattr(decl, "low", None), getattr(decl, "high", None)
    if low is None and high is None:
        return ""
    lo = "(" if not getattr(decl, "low_inclusive", True) else "["
    hi = ")" if not getattr(decl, "high_inclusive", True) else "]"
    low_text = "-inf" if low is None else f"{low:g}"
    high_text = "inf" if high is None else f"{high:g}"
    return f"{lo}{low_text}, {high_text}{hi}"


def _value(decl: Parameter) -> str:
    if decl.binding is not None:
        return "bound to the parent"
    return f"{decl.value:.6g}"


def _kind(decl: Variable) -> str:
    return "flow" if isinstance(decl, Flow) else "potential" if isinstance(decl, Potential) \
        else "field"


def _unit(unit: str) -> str:
    return "-" if unit in ("1", "") else unit


def component_reference(component: Component, heading: str = "###") -> str:
    """The component's documentation in the one template, as Markdown.

    Parameters
    ----------
    component : Component
        An instance (the declarations of a component depend on its constructor arguments; the
        instance shows them for one set).
    heading : str
        Markdown heading prefix of the section.

    Returns
    -------
    str
    """
    cls = type(component)
    doc = inspect.cleandoc(cls.__doc__ or "")
    summary = doc.split("\n\n", 1)[0].replace("\n", " ")
    lines = [f"{heading} `{cls.__module__}.{cls.__name__}`", "", summary, ""]
    args = constructor_arguments(cls)
    if args:
        lines += ["Constructor arguments: " + ", ".join(f"`{a}`" for a in args)
                  + " (see the class docstring for units and ranges).", ""]
    decls = component.declarations
    params = {k: d for k, d in decls.items() if isinstance(d, Parameter)}
    inputs = {k: d for k, d in decls.items() if isinstance(d, Input)}
    variables = {k: d for k, d in decls.items()
                 if isinstance(d, Variable) and not isinstance(d, Input)}
    if params:
        lines += ["| parameter | unit | value | range | description |", "|---|---|---|---|---|"]
        lines += [f"| `{k}` | {_unit(d.unit)} | {_value(d)} | {_range(d)} | {d.description} |"
                  for k, d in params.items()]
        lines.append("")
    if inputs:
        lines += ["| input | unit | default | description |", "|---|---|---|---|"]
        lines += [f"| `{k}` | {_unit(d.unit)} | "
                  f"{'' if d.default is None else f'{d.default:g}'} | {d.description} |"
                  for k, d in inputs.items()]
        lines.append("")
    if variables:
        lines += ["| variable | unit | description |", "|---|---|---|"]
        lines += [f"| `{k}` | {_unit(d.unit)} | {d.description} |" for k, d in variables.items()]
        lines.append("")
    connectors = component.connectors
    if connectors:
        lines += ["| connector | type | fields |", "|---|---|---|"]
        for k, c in connectors.items():
            fields = ", ".join(f"`{f}` [{_unit(d.unit)}] ({_kind(d)})"
                               for f, d in c.fields.items())
            lines.append(f"| `{k}` | {type(c).__name__} | {fields} |")
        lines.append("")
    children = Counter(type(c).__name__ for c in component.children.values())
    if children:
        lines += ["Sub-components: " + ", ".join(
            f"{n} x {name}" if n > 1 else name for name, n in children.items()) + ".", ""]
    return "\n".join(lines)
