"""The front door: :func:`simulate` with its :class:`SimConfig`, and the :class:`Results` it
returns (saved and loaded as netCDF)."""
