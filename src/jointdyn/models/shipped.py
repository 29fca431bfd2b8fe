"""What a shipped model is: one record the CLI and the studies read in place of a model file.

A shipped model is a builder with named arguments (CLI options and sweep parameters), a
*variant* argument that changes its structure (the slider-crank's ``joint``) and run-file hooks
(headline columns, summary, metric aliases). Generic code (:mod:`jointdyn.studies`,
:mod:`jointdyn.cli`) asks the record and never names a model; the catalogue of records is
:mod:`jointdyn.models.catalog`. Model-file keys (``joints.drive.omega``) apply to a shipped model
too: its built Model is encoded and the keys are set on that (:mod:`jointdyn.io.modelfile`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field


@dataclass(frozen=True)
class Shipped:
    """A shipped model.

    name            what the user types (``jointdyn run NAME``)
    variant_arg     name of the structural argument (e.g. ``joint``) and its default variant
    variants()      the valid variants
    numeric_args()  ``{name: (default, unit)}`` of the builder's number arguments (sweepable)
    flags           the non-numeric builder arguments (e.g. ``friction``, ``contact``)
    relevant(v)     the arguments that act on variant ``v``
    model_kw(v, given, option_names)  checked builder keyword arguments (one-line errors)
    build(v, **kw)  the :class:`~jointdyn.multibody.model.Model`
    config(v, revs, **run_kw)  its :class:`~jointdyn.simulation.simulate.SimConfig` for ``revs``
                    revolutions of its driver (``speed`` [rad/s] passed when given)
    run_args()      ``{name: default}`` of the run settings (``revs``, ``samples_per_rev``, tolerances)
    check_run(revs, samples_per_rev, rtol, atol, names)  their checks
    headline(res), summarize(res, cols, metrics, revs), aliases: run-file hooks
    title(v)        a run's title
    """

    name: str
    variant_arg: str
    default_variant: str
    variants: Callable[[], tuple[str, ...]]
    numeric_args: Callable[[], dict[str, tuple[float, str]]]
    flags: tuple[str, ...]
    relevant: Callable[[str], set[str]]
    model_kw: Callable[..., dict]
    build: Callable[..., object]
    config: Callable[..., object]
    run_args: Callable[[], dict]
    check_run: Callable[..., None]
    headline: Callable
    summarize: Callable
    aliases: dict[str, str] = field(default_factory=dict)
    title: Callable[[str], str] = str

    def arguments(self) -> tuple[str, ...]:
        """Every builder argument a sweep may set: the variant, the numbers and the flags."""
        return (self.variant_arg, *self.numeric_args(), *self.flags)

    def model(self, variant: str, given: dict, option_names: dict | None = None):
        """The Model of ``variant`` with the user's arguments ``given`` (checked)."""
        return self.build(variant, **self.model_kw(variant, given, option_names))

    def call(self, merged: dict, variants_in_sweep: set | None = None):
        """``(variant, model_kw, run_kw, revs)`` of one case given as ``{argument: value}``,
        checked. Arguments with no effect on this case's variant are dropped when they act on
        another variant of the sweep (``variants_in_sweep``), otherwise they are an error."""
        v = merged.get(self.variant_arg, self.default_variant)
        if not isinstance(v, str) or v not in self.variants():
            raise ValueError(f"{self.variant_arg} = {v!r}: unknown; valid: {', '.join(self.variants())}")
        names = self.arguments()
        given = {k: merged[k] for k in names if k in merged and k != self.variant_arg}
        for k in list(given):
            if variants_in_sweep and k not in self.relevant(v):
                if any(k in self.relevant(w) for w in variants_in_sweep):
                    del given[k]
        model_kw = self.model_kw(v, given)
        ra = self.run_args()
        run_kw = {k: merged[k] for k in ra if k in merged and k != "revs"}
        revs = merged.get("revs", ra["revs"])
        self.check_run(
            revs, run_kw.get("samples_per_rev", ra["samples_per_rev"]), run_kw.get("rtol"), run_kw.get("atol")
        )
        if "solver" in run_kw:
            from jointdyn.integrators import SOLVERS

            if run_kw["solver"] not in ("auto", *SOLVERS):
                raise ValueError(f"solver = {run_kw['solver']!r}: unknown; valid: {['auto', *SOLVERS]}")
        return v, model_kw, run_kw, float(revs)

    def setup(self, variant: str, revs: float, model_kw: dict | None = None, **run_kw):
        """``(Model, SimConfig)`` of ``variant`` for ``revs`` revolutions (at the case's own speed)."""
        kw = dict(model_kw or {})
        if "speed" in kw:
            run_kw = {**run_kw, "speed": kw["speed"]}
        return self.build(variant, **kw), self.config(variant, revs, **run_kw)
