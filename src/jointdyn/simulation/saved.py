"""Reading saved runs: netCDF files as xarray Datasets (checksums verified) and the compiled
system rebuilt from the model description stored in them."""

from __future__ import annotations

from jointdyn.multibody.system import System


def system_from_dict(d: dict) -> System:
    """Rebuild the compiled :class:`~jointdyn.multibody.system.System` from ``Model.to_dict()`` (the
    ``model`` attribute of a results file)."""
    from jointdyn.core.constraints import CONSTRAINTS
    from jointdyn.forces.contact_laws import CONTACT_LAWS
    from jointdyn.forces.elements import FORCE_ELEMENTS
    from jointdyn.forces.friction_laws import FRICTION_LAWS
    from jointdyn.multibody.model import Model

    def value(v):
        if isinstance(v, dict) and "law" in v:
            args = {k: value(x) for k, x in v.items() if k != "law"}
            return {**CONTACT_LAWS, **FRICTION_LAWS}[v["law"]](**args)
        return tuple(value(x) for x in v) if isinstance(v, list) else v

    m = Model(d["name"], tuple(d["gravity"]))
    for p, xy in d.get("ground_points", {}).items():
        m.add_ground_point(p, xy)
    for n, b in d["bodies"].items():
        m.add_body(n, **{k: (value(x) if k != "points" else x) for k, x in b.items()})
    for n, item in d["items"].items():
        args = {k: value(x) for k, x in item.items() if k != "type"}
        m.add(n, {**CONSTRAINTS, **FORCE_ELEMENTS}[item["type"]](**args))
    return m.compile()


def load_dataset(path):
    """Read any jointdyn netCDF file (``results.nc``, ``sweep.nc``) as an xarray Dataset,
    verifying the stored checksums; corruption raises a one-line ``ValueError``."""
    import xarray as xr

    try:
        return xr.load_dataset(path, engine="h5netcdf")
    except FileNotFoundError:
        raise
    except (OSError, ValueError, KeyError) as err:  # h5py: "filter returned failure" = bad checksum
        msg = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise ValueError(f"{path}: unreadable or corrupt netCDF file ({msg})") from None
