"""Demos of the engine, run with ``python -m demos`` (see :mod:`demos.cli`).

Each module here that defines ``DEMO = demos.cli.Demo(...)`` is found automatically.
"""
