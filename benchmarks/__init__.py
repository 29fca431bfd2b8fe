"""Speed and accuracy benchmarks: ``python -m benchmarks`` prints the table."""
