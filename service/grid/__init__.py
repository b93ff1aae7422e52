"""The grid: axes, the design basis and the expansion of a study into runs with stable ids."""
