"""The exact models: a lesson's contacts, each at its exact moment, as the closed form gives it.

A ball's impacts with walls and with other balls found in time order within a step
(``contacts``, ``sweep``, ``sweep_one``, ``sweep_paths``, ``bent_paths``, ``pair_impacts``,
``pair_order``, ``pair_plan``, ``pair_bounce``, ``collisions``), resting, sliding and rolling
on a face (``resting``), piles that rest on one another (``pile``, ``pile_rows``, ``soft``,
``shape_impacts``), sleep (``sleep``), bodies pushed out of a wall (``push_out``,
``overlaps``), the Newton solve of joints held to 1e-9 m (``joint_solver``, ``joint_rows``,
``joint_contacts``) and springs in closed form (``spring_step``). ``World(solver="exact")``
runs them; ``solver="auto"`` does for a scene that a contact cannot push a body with corners
in. A module here imports the core, ``engine.geometry``, ``engine.dynamics`` and this folder.
"""
