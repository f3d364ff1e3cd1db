"""``hamta bench``: the measuring instrument beside the engine (imports ``hamta.core``, never the reverse).

Synthetic families with exact ground truth and the real development pairs (:mod:`.families`,
:mod:`.cases`), the judgement of a returned mapping (:mod:`.metrics`), the runner (:mod:`.runner`),
its tables (:mod:`.tables`) and each paper's own evaluation and the engineering goals (:mod:`.study`, :mod:`.studies`).
"""
