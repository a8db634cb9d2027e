"""The ground floor: the primitives every other room uses.

Each module holds one fact of the package, and imports nothing above this room:

* :mod:`~frictionlaws.base.errors`: the exceptions and warnings (an
  :class:`~frictionlaws.base.errors.InputError` names file, column and row), and the
  pieces of an error message;
* :mod:`~frictionlaws.base.numbers`: the one parser of numbers written as text;
* :mod:`~frictionlaws.base.units`: the one unit table (SI inside, display units at the
  edges) and the one unit grammar;
* :mod:`~frictionlaws.base.limits`: the bounds on what is read (sizes, nesting, lengths);
* :mod:`~frictionlaws.base.sanitize`: cells and lines of text as they are read and written;
* :mod:`~frictionlaws.base.outputs`: the output guard (never overwrite an input, never
  leave a partial file);
* :mod:`~frictionlaws.base.jsonio`: the one strict JSON reader and encoder;
* :mod:`~frictionlaws.base.display`: the display units of result views;
* :mod:`~frictionlaws.base.lazy`: package attributes loaded on first use.

Import from the module that defines a name; this package imports none of them.
"""

__all__: list[str] = []
