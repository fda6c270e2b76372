; t004_left_uneven: left hand, uneven
teeth    = 4
steps    = 91.651, 90.719, 89.817, 87.813
diameter = 18000
lead     = 150000
hand     = left
noise    = 0.02
blur     = 0.5
image    = 640
seed     = 135
