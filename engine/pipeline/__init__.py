"""The pipeline: one step of a World in stage order, and what a game asks of it between steps.

The soft step top to bottom (``game_step``: pairs, manifolds, the solve, continuous, events,
sleep; ``game_broadphase``, ``game_contacts``, ``game_loop``, ``game_sleep``), the exact
models' step (``stepping``), which solver a World runs (``solver_choice``), the World's state
and membership (``world_state``, ``membership``), events and callbacks (``event_dispatch``,
``body_sensors``, ``collision_handlers``), queries (``queries``), reading state for drawing
(``readout``) and snapshots (``snapshot``, ``snapshot_materials``). A module here may import
any folder below it; only the doors import this folder (``engine.world``, and the package for
``SolverWarning``).
"""
