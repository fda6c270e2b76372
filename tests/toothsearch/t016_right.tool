; t016_right
teeth    = 16
steps    = even
diameter = 60000
lead     = 400000
hand     = right
noise    = 0.03
blur     = 1.5
image    = 768
seed     = 212
