"""The similarity measure the independent check and the matchers share: CFOG structural features
(:mod:`.cfog`) and the sub-pixel peak of a correlation surface (:mod:`.peak`).

It lies below the descriptors, the matchers and the check (:mod:`hamta.core.verify`), so that the check,
which must judge a model independently of how it was matched, imports none of them.
"""
