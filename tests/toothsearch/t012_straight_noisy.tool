; t012_straight_noisy: worst noise and blur
teeth    = 12
steps    = even
diameter = 50000
lead     = 0   ; straight flutes
hand     = right
noise    = 0.05
blur     = 2
image    = 768
seed     = 191
