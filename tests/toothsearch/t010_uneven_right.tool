; t010_uneven_right
teeth    = 10
steps    = 32.742, 32.448, 38.189, 36.265, 33.218, 37.178, 37.946, 38.273, 35.589, 38.152
diameter = 45000
lead     = 1000000
hand     = right
noise    = 0.02
blur     = 2
image    = 768
seed     = 184
