; t036_right
teeth    = 36
steps    = even
diameter = 100000
lead     = 1500000
hand     = right
noise    = 0.05
blur     = 1
image    = 896
seed     = 254
