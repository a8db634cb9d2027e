"""Build shim for the package list (all other metadata is in pyproject.toml).

setuptools' ``packages.find`` cannot add a package that lives outside the
``frictionlaws/`` tree, and the packaged datasets live in the top-level
``datasets/`` directory, installed as ``frictionlaws._datasets`` (see
``[tool.setuptools.package-dir]`` in pyproject.toml).  So the package list is
every ``frictionlaws`` sub-package found on disk, plus that one.
"""

from setuptools import find_packages, setup

setup(
    packages=[*find_packages(include=["frictionlaws", "frictionlaws.*"]),
              "frictionlaws._datasets"],
)
