; t060_left
teeth    = 60
steps    = even
diameter = 130000
lead     = 800000
hand     = left
noise    = 0.04
blur     = 1.5
image    = 1024
seed     = 282
