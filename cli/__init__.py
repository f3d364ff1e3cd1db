"""The ``hamta`` command line: a front end over :mod:`hamta.core` (and :mod:`hamta.bench` for ``hamta bench``)."""
