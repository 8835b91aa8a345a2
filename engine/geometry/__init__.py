"""Geometry: shapes and what they tell about each other, with no time and no mass in motion.

The shapes (``colliders``: circles, boxes, polygons, capsules, segments; ``convex``; ``mass``:
areas and moments), the time of impact of a ball on a known path (``impact``), the contact
manifold of two shapes (``manifold``, ``manifold_kinds``, ``manifold_polygon``, ``narrowphase``,
``shaped``), and the grids that say which pairs may touch at all (``faces``, ``face_grid``,
``face_grid_edits``, ``cell_table``, ``face_looks``, ``pair_grid``, ``pair_math``,
``query_grid``, ``sensors``). A module here imports only the engine's core and this folder.
"""
