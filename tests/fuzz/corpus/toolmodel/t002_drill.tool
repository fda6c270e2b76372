; t002_drill: twist drill, short lead
teeth    = 2
steps    = even
diameter = 10000
lead     = 50000
hand     = right
noise    = 0.01
blur     = 1
image    = 512
seed     = 100
