"""The dicts mcws's results are: keys also attributes."""


class _Record(dict):
    """A dict whose keys are also attributes (names starting with _ excepted)."""

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None
