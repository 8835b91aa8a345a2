"""The demos' sprites (ant.png, ant_small.png, ant_top.png, car.png): package data, in a wheel too.

``make_assets.py`` redraws them; ``make_readme_images.py`` makes the README's pictures.
"""
