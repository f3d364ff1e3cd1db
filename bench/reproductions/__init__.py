"""Reproductions of each paper's own evaluation, run by ``hamta bench`` next to the family tables
(see :mod:`hamta.bench.study`)."""
