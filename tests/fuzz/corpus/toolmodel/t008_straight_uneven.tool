; t008_straight_uneven: straight, uneven
teeth    = 8
steps    = 48.069, 49.391, 45.902, 42.967, 42.186, 42.436, 40.883, 48.166
diameter = 32000
lead     = 0   ; straight flutes
hand     = left
noise    = 0.04
blur     = 1.8
image    = 768
seed     = 170
