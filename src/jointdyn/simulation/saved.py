"""Reading saved runs: netCDF files as xarray Datasets (checksums verified) and the compiled
arrays of the system stored with them."""

from __future__ import annotations

import numpy as np


def load_arrays(path) -> dict | None:
    """The compiled arrays of the system (group ``system`` of a ``results.nc``, see
    ``System.ARRAYS``), None if the file has none (written before they were stored)."""
    import h5netcdf

    try:
        with h5netcdf.File(path, "r") as f:
            if "system" not in f.groups:
                return None
            g = f.groups["system"]
            return {k: np.asarray(v[...]).reshape(v.shape) for k, v in g.variables.items()}
    except (OSError, ValueError, KeyError) as err:  # h5py: "filter returned failure" = bad checksum
        msg = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise ValueError(f"{path}: unreadable or corrupt netCDF file ({msg})") from None


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
