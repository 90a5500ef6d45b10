# SPDX-License-Identifier: MIT
"""The read-only attributes that the package's classes pass on from their compiled object."""


def forwarded(name, doc):
    """A property that reads `name` of the object's compiled part (self._impl), with `doc`."""

    def read(self):
        return getattr(self._impl, name)

    read.__name__ = name
    return property(read, doc=doc)
