"""Local descriptors computed on scale-normalised patches."""
