"""Dynamics: what moves bodies, step by step, and what holds them together.

The World's per-body arrays (``store``), the forces and torques compiled once (``forcefield``,
``torquefield``, ``affine``), turning (``rotation``), the method's choice (``policy``), the
joints a game makes (``links``: rods, cables, pins; ``joints``: hinges and welds;
``constraints``: pymunk's slide, groove, gear and ratchet; ``springs``; ``mouse_joint``), the
soft step's solver (``solver``: Box2D v3's substeps, with ``coloring``, ``game_joints`` and
``game_continuous``), and the contacts' ledger of what began and ended (``events``,
``pair_events``). A module here imports the core, ``engine.geometry`` and this folder.
"""
