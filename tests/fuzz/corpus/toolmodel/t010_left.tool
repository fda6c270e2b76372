; t010_left
teeth    = 10
steps    = even
diameter = 36000
lead     = 500000
hand     = left
noise    = 0.03
blur     = 1
image    = 768
seed     = 177
