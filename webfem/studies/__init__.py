"""Studies: sweeps of models against references. They use models/ and write through io/."""
