; t006_uneven_right: uneven, helical
teeth    = 6
steps    = 56.306, 59.027, 57.325, 56.063, 67.336, 63.943
diameter = 25000
lead     = 300000
hand     = right
noise    = 0.03
blur     = 1.2
image    = 640
seed     = 149
