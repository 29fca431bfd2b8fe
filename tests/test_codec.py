"""The model codec: every registry entry (constraints, force elements, film models with each
cavitation condition, contact and friction laws) round-trips Model → dict → TOML → dict → Model
to an equal model and an identical compiled System, through the model-file loader too, and
through Results.save → load (the system rebuilt from the stored arrays, nothing compiled)."""

import dataclasses
import tomllib
import warnings

import numpy as np
import pytest

from jointdyn import post
from jointdyn.core.constraints import CONSTRAINTS
from jointdyn.errors import ModelError, PhysicsWarning
from jointdyn.film.cavitation import condition
from jointdyn.film.cavitation import names as cavitation_names
from jointdyn.film.models import FILM_MODELS, Finite
from jointdyn.forces.contact_laws import CONTACT_LAWS
from jointdyn.forces.elements import FORCE_ELEMENTS, NMEM, NOUT, output_slots
from jointdyn.forces.friction_laws import FRICTION_LAWS
from jointdyn.forces.journal import ClearanceJoint, JournalBearing
from jointdyn.io.modelfile import build, dumps
from jointdyn.multibody import codec
from jointdyn.multibody.model import Model
from jointdyn.multibody.system import System
from jointdyn.simulation.results import Results
from jointdyn.simulation.simulate import SimConfig


def _non_default(obj):
    """``obj`` with every non-zero float field that still has its default scaled by 0.9, so a
    field the codec dropped would come back different."""
    change = {}
    for f in dataclasses.fields(obj):
        v = getattr(obj, f.name)
        if isinstance(v, float) and v != 0.0 and v == f.default:
            change[f.name] = 0.9 * v
    return dataclasses.replace(obj, **change)


def _dynamic_conditions():
    """The conditions the dynamic ``finite`` film takes (a mass-conserving one needs history)."""
    return [c for c in cavitation_names() if not condition(c).mass_conserving]


def _cases():
    out = [(f"joints.{n}", _non_default(cls.example())) for n, cls in CONSTRAINTS.items()]
    for name, cls in FORCE_ELEMENTS.items():
        if cls is JournalBearing:
            for film, fcls in FILM_MODELS.items():
                films = (
                    [Finite(cavitation=c) for c in _dynamic_conditions()]
                    if fcls is Finite
                    else [fcls(), film]
                )
                out += [(f"elements.{name}[{f!r}]", _non_default(cls.example(film=f))) for f in films]
        else:
            out.append((f"elements.{name}", _non_default(cls.example())))
    dry = ClearanceJoint.example()
    for name, law in CONTACT_LAWS.items():
        out.append((f"contact.{name}", dataclasses.replace(dry, contact=_non_default(law.example()))))
    for name, law in FRICTION_LAWS.items():
        out.append((f"friction.{name}", dataclasses.replace(dry, friction=_non_default(law.example()))))
    return out


CASES = _cases()


def _model(item) -> Model:
    """Two free bodies "a", "b" with points "A", "B" (the examples' names) joined by ``item``."""
    m = Model("codec pair", gravity=(0.3, -9.7))
    m.add_ground_point("O", (0.01, 0.02))
    m.add_body("a", 1.1, 1.2e-3, position=(0.0, 0.0), angle=0.05, points={"A": (0.03, -0.01)})
    m.add_body(
        "b", 0.9, 0.8e-3, position=(0.05, -0.035), velocity=(0.1, 0.0, 2.0), points={"B": (-0.02, 0.015)}
    )
    m.add("item", item)
    return m


def _compile(m: Model) -> System:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)  # short-bearing example beyond its L/D
        return m.compile()


def assert_same_model(a: Model, b: Model):
    assert (a.name, a.gravity, a.ground_points) == (b.name, b.gravity, b.ground_points)
    assert a.bodies == b.bodies
    assert a.items == b.items  # the dataclasses' equality: every field, laws included
    assert [type(x) for x in a.items.values()] == [type(x) for x in b.items.values()]


def assert_same_system(a: System, b: System):
    for k in ("name", "body_names", "constraint_names", "constraint_rows", "element_names", "n_rows"):
        assert getattr(a, k) == getattr(b, k), k
    assert a.constraints == b.constraints and a.elements == b.elements
    assert a.gravity == b.gravity and a.model_dict == b.model_dict
    for k in System.ARRAYS:
        x, y = getattr(a, k), getattr(b, k)
        assert x.dtype == y.dtype, k
        np.testing.assert_array_equal(x, y, err_msg=k)


def test_every_registry_entry_is_covered():
    names = {n.split("[")[0] for n, _ in CASES}
    assert {f"joints.{n}" for n in CONSTRAINTS} <= names
    assert {f"elements.{n}" for n in FORCE_ELEMENTS} <= names
    assert {f"contact.{n}" for n in CONTACT_LAWS} | {f"friction.{n}" for n in FRICTION_LAWS} <= names
    films = [x.film for n, x in CASES if isinstance(x, JournalBearing)]
    assert {type(f) for f in films if not isinstance(f, str)} == set(FILM_MODELS.values())
    assert {f.cavitation for f in films if isinstance(f, Finite)} == set(_dynamic_conditions())


@pytest.mark.parametrize("item", [c for _, c in CASES], ids=[n for n, _ in CASES])
def test_model_dict_toml_round_trip(item):
    m = _model(item)
    d = m.to_dict()
    text = codec.to_toml(d)
    assert codec.from_toml(text) == d  # the TOML text is the dict, exactly (floats by repr)
    back = Model.from_dict(codec.from_toml(text))
    assert_same_model(back, m)
    assert back.to_dict() == d
    assert_same_system(_compile(back), _compile(m))
    # the validating model-file reader builds the same model from the dumped file
    config = SimConfig(t_end=1e-3, n_out=3, rtol=1e-7)
    text = dumps(m, config)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)
        read, read_config = build(tomllib.loads(text), "<dumped>", text, assemble=False)
    assert_same_model(read, m)
    assert read_config == config


def _synthetic_results(system: System, nt: int = 5) -> Results:
    """Results with deterministic arrays of the right shapes: save/load is storage only, so its
    test needs no integration (the end-to-end test runs a real one)."""
    rng = np.random.default_rng(11)
    ne = len(system.element_names)
    return Results(
        system=system,
        t=np.linspace(0.0, 1e-3, nt),
        y=system.y0 + 1e-4 * rng.normal(size=(nt, 2 * system.n)),
        mem=rng.normal(size=(nt, ne, NMEM)),
        qdd=rng.normal(size=(nt, system.n)),
        lam=rng.normal(size=(nt, system.n_rows)),
        eout=rng.normal(size=(nt, ne, NOUT)),
        drift=np.abs(rng.normal(size=(nt, 2))),
        stats={"accepted_steps": 4},
        wall_time=0.5,
        config={"solver": "dopri5", "rtol": 1e-7},
    )


@pytest.mark.parametrize("item", [c for _, c in CASES], ids=[n for n, _ in CASES])
def test_results_save_load_gives_the_same_system(item, tmp_path, monkeypatch):
    res = _synthetic_results(_compile(_model(item)))
    f = tmp_path / "r.nc"
    res.save(f)

    def no_compile(*a, **k):
        raise AssertionError("loading a results file compiled the model")

    monkeypatch.setattr(Model, "compile", no_compile)
    back = Results.load(f)
    assert_same_system(back.system, res.system)
    for a in ("t", "y", "mem", "qdd", "lam", "eout", "drift"):
        np.testing.assert_array_equal(getattr(back, a), getattr(res, a), err_msg=a)
    s = res.system
    for name, el in zip(s.element_names, s.elements):
        for o in output_slots(el):
            np.testing.assert_array_equal(back.element(name, o), res.element(name, o))
        assert post.dissipated_energy(back, name) == post.dissipated_energy(res, name)
    for name, c in zip(s.constraint_names, s.constraints):
        np.testing.assert_array_equal(back.multipliers(name), res.multipliers(name))
        if type(c).__name__ == "Revolute":
            np.testing.assert_array_equal(post.joint_reaction(back, name), post.joint_reaction(res, name))
    assert back.journals() == res.journals()
    for name in res.journals():
        np.testing.assert_array_equal(back.orbit(name)[0], res.orbit(name)[0])
        assert post.max_penetration(back, name) == post.max_penetration(res, name)
        for k, v in post.film_states(res, name).items():
            np.testing.assert_array_equal(post.film_states(back, name)[k], v)
        if isinstance(back.system.elements[back.system.element_names.index(name)], JournalBearing):
            for k, v in post.film_outputs(res, name).items():  # from the stored film table
                np.testing.assert_array_equal(post.film_outputs(back, name)[k], v)


def test_results_of_the_previous_layout_still_load(tmp_path):
    """A results file written before the codec: ``model`` in the old layout ({name, gravity,
    bodies, ground_points, items}) and no stored arrays: the model is compiled, as before."""
    import json

    import h5py

    item = JournalBearing.example(film=Finite(cavitation="reynolds"))
    res = _synthetic_results(_compile(_model(item)))
    d = res.system.model_dict
    old = {
        "name": d["model"]["name"],
        "gravity": d["model"]["gravity"],
        "bodies": d["bodies"],
        "ground_points": d["ground"]["points"],
        "items": {**d["joints"], **d["elements"]},
    }
    f = tmp_path / "old.nc"
    res.save(f)
    with h5py.File(f, "a") as h:
        h.attrs["model"] = json.dumps(old)
        del h["system"]
    back = Results.load(f)
    assert_same_system(back.system, res.system)


def test_unknown_law_is_a_one_line_model_error():
    d = _model(ClearanceJoint.example()).to_dict()
    d["elements"]["item"]["contact"]["law"] = "nope"
    with pytest.raises(ModelError, match=r"unknown contact law 'nope'; valid names: \['flores'"):
        Model.from_dict(d)
