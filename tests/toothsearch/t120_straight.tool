; t120_straight
teeth    = 120
steps    = even
diameter = 180000
lead     = 0   ; straight flutes
hand     = right
noise    = 0.03
blur     = 1.5
image    = 1152
seed     = 310
