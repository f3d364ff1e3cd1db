"""Keypoint detectors and the response maps they work on (scale spaces, phase congruency, edges, lines)."""
