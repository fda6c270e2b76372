; t014_right
teeth    = 14
steps    = even
diameter = 55000
lead     = 2000000
hand     = right
noise    = 0.02
blur     = 1
image    = 768
seed     = 205
