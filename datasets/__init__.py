"""The packaged datasets (data files only; installed as ``frictionlaws._datasets``)."""

__all__: list[str] = []
