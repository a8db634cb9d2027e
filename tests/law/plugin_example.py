"""A third-party law, as a plugin package would declare it (used by test_plugins.py)."""

from frictionlaws.law import Law, Param

LAW = Law(
    id="plugin-linear-p",
    title="Plugin example: linear in pressure",
    family="sliding",
    variables=("p",),
    params=(Param("mu0", "", 1.0, (0, 10), "mu at p = 0"),
            Param("k", "1/Pa", 0.0, (-1, 1), "slope")),
    formula=lambda m, p, mu0, k: mu0 + k * p,
    references=("test",),
    description="Used by the plugin-loading test only.",
)


def broken():
    raise RuntimeError("this plugin is broken on purpose")
