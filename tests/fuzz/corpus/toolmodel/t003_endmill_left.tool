; t003_endmill_left: three-flute end mill, left hand
teeth    = 3
steps    = even
diameter = 12000
lead     = 60000
hand     = left
noise    = 0.02
blur     = 1
image    = 640
seed     = 114
