; t090_left
teeth    = 90
steps    = even
diameter = 150000
lead     = 1000000
hand     = left
noise    = 0.03
blur     = 1.5
image    = 1024
seed     = 296
