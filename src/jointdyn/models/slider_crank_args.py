"""Arguments of the shipped slider-crank (CLI options and sweep parameters), checked at the edge.

The argument names, defaults and units come from the builder's signature and docstring
(:func:`jointdyn.models.slider_crank.slider_crank`) and the integration settings from
:func:`jointdyn.models.slider_crank.slider_crank_config`; the joint kinds from the film-model registry. What
is decided here is which argument acts on which joint kind, the allowed ranges and the
plausibility bounds ([T140]). Every problem is one ``ValueError`` naming the option, its unit
and the allowed range; implausible-but-possible values give a :class:`PhysicsWarning`.
"""

from __future__ import annotations

import inspect
import re
import warnings

from jointdyn.core.checks import FieldError, check
from jointdyn.errors import PhysicsWarning
from jointdyn.film.models import FILM_MODELS
from jointdyn.models import slider_crank as sc
from jointdyn.models.shipped import Shipped

#: arguments of the builder that are numbers (sweepable), with their units from its docstring
_DOC_UNIT = re.compile(r"(\w+)(?::[^;\[]*)?\s*\[([^\]]+)\]")


def builder_args() -> dict[str, tuple[float, str]]:
    """``{name: (default, unit)}`` for the numeric arguments of the slider-crank builder."""
    units = dict(_DOC_UNIT.findall(sc.slider_crank.__doc__ or ""))
    out = {}
    for name, p in inspect.signature(sc.slider_crank).parameters.items():
        if isinstance(p.default, float):
            out[name] = (p.default, units.get(name, "-"))
    return out


def run_args() -> dict[str, object]:
    """``{name: default}`` of the integration settings of a slider-crank run."""
    from jointdyn.models.slider_crank import slider_crank_config

    sig = inspect.signature(slider_crank_config)
    return {n: p.default for n, p in sig.parameters.items() if n not in ("joint", "speed")}


def joints() -> tuple[str, ...]:
    """Joint kinds of the piston pin: ``perfect``, ``dry`` and every registered film model."""
    return ("perfect", "dry", *FILM_MODELS)


#: non-numeric builder arguments the command line sets (besides the numeric ``builder_args``)
FLAGS = ("friction", "contact", "shear", "bushing")


def relevant(joint: str) -> set[str]:
    """Builder arguments that act for ``joint`` (``friction``/``asperity_height`` of a
    lubricated joint act only with ``contact``)."""
    common = {"speed", "gravity"}
    if joint == "perfect":
        return common
    if joint == "dry":
        return common | {"clearance", "restitution", "friction", "bushing"}
    return common | {
        "clearance",
        "viscosity",
        "length",
        "contact",
        "asperity_height",
        "friction",
        "shear",
        "bushing",
    }


#: allowed ranges (errors) and plausibility bounds (PhysicsWarning) [T140]
RULES = {
    "speed": "!= 0",
    "gravity": "in [-1000, 1000]",
    "clearance": f"in (0, {sc.JOURNAL_RADIUS}]",
    "viscosity": "in (0, 1000]",
    "length": "in (0, 1]",
    "restitution": "in (0, 1]",
    "asperity_height": ">= 0",
    "friction": "in [0, 2]",
    "revs": "> 0",
    "rtol": "in [1e-14, 0.01]",
    "atol": "in (0, 1)",
}
PLAUSIBLE = {
    "clearance": (0.1 * sc.JOURNAL_RADIUS, "radial clearance above 10 % of the journal radius"),
    "viscosity": (10.0, "viscosity above heavy gear oils (10 Pa·s)"),
    "friction": (1.0, "friction coefficient above 1 (clean dry metals)"),
}
NOTES = {
    "clearance": "a radial clearance beyond the journal radius is not a journal bearing",
    "viscosity": "beyond 1000 Pa·s the film is a near-rigid constraint: use joint 'perfect'",
    "rtol": "looser tolerances do not resolve the film and contact dynamics",
    "length": "bearing length",
}


def check_value(name: str, value, unit: str, option: str | None = None):
    """Range check (error) and plausibility check (warning) of one argument."""
    label = option or name
    rule = RULES.get(name, "finite")
    check(label, value, unit, rule, note=NOTES.get(name, ""))
    if name in PLAUSIBLE and abs(value) > PLAUSIBLE[name][0]:
        bound, what = PLAUSIBLE[name]
        msg = f"{label} = {value!r} [{unit}]: {what} (> {bound:g}); results may be unphysical"
        warnings.warn(msg, PhysicsWarning, stacklevel=2)
    return value


def slider_crank_args(joint: str, given: dict, option_names: dict | None = None) -> dict:
    """Builder keyword arguments of the slider-crank for ``joint`` from the arguments the user
    ``given`` (name -> value; absent = default). Irrelevant or conflicting arguments and
    out-of-range values are errors; ``option_names`` maps an argument to how the user wrote it
    (e.g. ``--clearance``) for the messages. ``friction`` is a coefficient [-]; ``contact`` a
    bool (Lankarani–Nikravesh asperity contact of a lubricated joint)."""
    from jointdyn.forces.contact_laws import LankaraniNikravesh, journal_bearing_stiffness
    from jointdyn.forces.friction_laws import Ambrosio
    from jointdyn.forces.journal import ASPERITY_MAX

    names = option_names or {}
    if joint not in joints():
        raise ValueError(f"{names.get('joint', 'joint')} = {joint!r}: unknown; valid: {', '.join(joints())}")
    args = builder_args()
    for k in given:
        if k not in args and k not in FLAGS:
            valid = sorted(args) + list(FLAGS)
            raise ValueError(f"{names.get(k, k)}: not an argument of the slider-crank; valid: {valid}")
    bad = [k for k in given if k not in relevant(joint)]
    if bad:
        shown = ", ".join(names.get(k, k) for k in bad)
        raise ValueError(f"{shown}: no effect on a {joint!r} joint (it acts on {_acts(bad[0])}); remove it")
    lubricated = joint not in ("perfect", "dry")
    contact = bool(given.get("contact", False))
    for k in ("friction", "asperity_height"):
        if lubricated and k in given and not contact:
            raise ValueError(
                f"{names.get(k, k)}: acts only in asperity contact of a lubricated joint; add "
                f"{names.get('contact', 'contact = true')} or remove it"
            )
    kw: dict = {}
    for k, v in given.items():
        if k in args:
            kw[k] = check_value(k, v, args[k][1], names.get(k))
    clearance = kw.get("clearance", args["clearance"][0])
    if "asperity_height" in kw and not kw["asperity_height"] <= ASPERITY_MAX * clearance:
        raise FieldError(
            names.get("asperity_height", "asperity_height"),
            kw["asperity_height"],
            "m",
            f"<= clearance/2 = {ASPERITY_MAX * clearance:.6g} (a roughness, not a gap)",
        )
    if "friction" in given:
        mu = check_value("friction", given["friction"], "-", names.get("friction"))
        if mu > 0:
            kw["friction"] = Ambrosio(coefficient=mu)
    if "bushing" in given:
        if given["bushing"] not in ("rod", "slider"):
            raise ValueError(f"{names.get('bushing', 'bushing')} = {given['bushing']!r}: valid: rod, slider")
        kw["bushing"] = given["bushing"]
    if "shear" in given:
        kw["shear"] = bool(given["shear"])
    if contact:
        rb = sc.JOURNAL_RADIUS + clearance
        K = journal_bearing_stiffness(rb, sc.JOURNAL_RADIUS, sc.YOUNG, sc.POISSON, sc.YOUNG, sc.POISSON)
        kw["contact"] = LankaraniNikravesh(stiffness=K, exponent=1.5, restitution=sc.RESTITUTION)
    return kw


def shipped_model(joint: str, given: dict, option_names: dict | None = None):
    """The slider-crank :class:`~jointdyn.multibody.model.Model` with piston-pin ``joint`` and
    the user's arguments ``given`` (checked by :func:`slider_crank_args`; SI)."""
    return sc.slider_crank(joint, **slider_crank_args(joint, given, option_names))


def _acts(name: str) -> str:
    kinds = [j for j in joints() if name in relevant(j)]
    lub = [j for j in kinds if j not in ("perfect", "dry")]
    parts = [j for j in kinds if j in ("perfect", "dry")] + (["lubricated joints"] if lub else [])
    return " and ".join(parts) or "no joint"


def check_run(revs, samples_per_rev, rtol=None, atol=None, names: dict | None = None) -> None:
    """Integration settings of a slider-crank run: ranges, at least one output interval."""
    n = names or {}
    check_value("revs", revs, "revolutions", n.get("revs"))
    check(n.get("samples_per_rev", "samples_per_rev"), samples_per_rev, "-", ">= 2", integer=True)
    if revs * samples_per_rev < 1:
        raise FieldError(
            n.get("revs", "revs"),
            revs,
            "revolutions",
            f">= 1/samples_per_rev = {1 / samples_per_rev:.3g}",
            note="at least one output interval",
        )
    for k, v in (("rtol", rtol), ("atol", atol)):
        if v is not None:
            check_value(k, v, "-", n.get(k))


def _build(joint: str, **kw):
    return sc.slider_crank(joint, **kw)


#: the shipped slider-crank as a catalogue record (:mod:`jointdyn.models.catalog`)
SLIDER_CRANK = Shipped(
    name="slider-crank",
    variant_arg="joint",
    default_variant="perfect",
    variants=joints,
    numeric_args=builder_args,
    flags=("friction", "contact"),
    relevant=relevant,
    model_kw=slider_crank_args,
    build=_build,
    config=sc.slider_crank_config,
    run_args=run_args,
    check_run=check_run,
    headline=sc.headline,
    summarize=sc.summarize,
    aliases=sc.METRIC_ALIASES,
    title=lambda joint: f"slider-crank, {joint} piston pin",
)
