; t048_right
teeth    = 48
steps    = even
diameter = 120000
lead     = 2000000
hand     = right
noise    = 0.03
blur     = 2
image    = 1024
seed     = 268
