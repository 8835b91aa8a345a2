"""The demos' sprites (ant.png, ant_small.png, car.png) as package data, found in a wheel too.

``make_assets.py`` redraws them; ``make_readme_images.py`` makes the README's pictures.
"""
