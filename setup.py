"""The repository root is the package ``hamta`` (and the QGIS plugin folder): map it and discover
every sub-package, so that a wheel carries the whole package. Everything else is in pyproject.toml."""
from setuptools import find_packages, setup

setup(package_dir={"hamta": "."},
      packages=["hamta"] + ["hamta." + p for p in find_packages(".", exclude=["tests", "tests.*"])])
