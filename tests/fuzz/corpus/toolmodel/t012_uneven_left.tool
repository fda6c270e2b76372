; t012_uneven_left
teeth    = 12
steps    = 27.263, 32.091, 27.615, 32.329, 30.381, 27.264, 29.008, 30.04, 33.524, 32.927, 27.104, 30.454
diameter = 50000
lead     = 250000
hand     = left
noise    = 0.01
blur     = 0.8
image    = 768
seed     = 198
