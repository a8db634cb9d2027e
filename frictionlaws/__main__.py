"""``python -m frictionlaws``: the same as the ``frictionlaws`` command."""

from frictionlaws.cli import entry

__all__: list[str] = []

if __name__ == "__main__":
    entry()
