; t003_uneven: three uneven flutes
teeth    = 3
steps    = 111.976, 126.787, 121.237
diameter = 16000
lead     = 100000
hand     = right
noise    = 0.05
blur     = 1.5
image    = 640
seed     = 121
