"""Files: atomic writes, run directories (lock, manifest), the output contract of a run, model
files (TOML), and signals as a flag."""
