; t030_left
teeth    = 30
steps    = even
diameter = 90000
lead     = 900000
hand     = left
noise    = 0.04
blur     = 2
image    = 896
seed     = 240
