; t004_endmill_noisy: worst noise and blur
teeth    = 4
steps    = even
diameter = 20000
lead     = 80000
hand     = right
noise    = 0.05
blur     = 2
image    = 640
seed     = 128
