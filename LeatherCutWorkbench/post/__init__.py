"""Machine-file writers, machine profiles and the live machine link."""
