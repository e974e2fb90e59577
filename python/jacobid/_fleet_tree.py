# SPDX-License-Identifier: MIT
"""identify's ordered merge (identify::OrderedMerge, host-tools/src/identify/pipeline/segmented_pipeline.cpp) over
Dask futures, for jacobid.fleet (docs/fleet.md, "The merge order").

Items are added in the logs' order as soon as each is known to be good; two adjacent partial results of the same
level are merged at once (a binary counter), so the merges run while the other logs are still being factored
instead of after the last one. At the end the carried-up odd ones join from the right: the bracketing of the
level-by-level pairing (adjacent pairs, then adjacent pairs of those, an odd last one carried up), hence the
same bits as ``jacobid identify --in ...`` whatever the scheduling.
"""


class OrderedTree:
    """The ordered tree reduction of futures, built as they are added. merge(left, right) submits one merge (a
    future); result() is the future of everything added, merged (None when nothing was)."""

    def __init__(self, merge):
        self._merge = merge
        self._stack = []  # (level, partial result) in the items' order

    def add(self, item):
        self._stack.append((0, item))
        while len(self._stack) > 1 and self._stack[-1][0] == self._stack[-2][0]:
            level, right = self._stack.pop()
            _, left = self._stack.pop()
            self._stack.append((level + 1, self._merge(left, right)))

    def result(self):
        while len(self._stack) > 1:
            _, right = self._stack.pop()
            level, left = self._stack.pop()
            self._stack.append((level, self._merge(left, right)))
        return self._stack[0][1] if self._stack else None
