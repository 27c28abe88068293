"""bhnsid sequence: constant-rest-mass sequences, the ISCO and its error bars (sequence/README.md)."""
