/* libmodbus, loaded with dlopen when a Modbus server opens (mb_open):
 * linked directly, every `s42 run` mapped it for the few that serve.
 * modbus.c includes this after <modbus/modbus.h> and calls the functions
 * by their usual names; one it calls and this table lacks does not link. */
#ifndef S42_MODBUS_DL_H
#define S42_MODBUS_DL_H

#include <modbus/modbus.h>
#include <stddef.h>

#define S42_MODBUS_SONAME "libmodbus.so.5"

#define S42_MODBUS_FNS(F) \
  F(modbus_free) \
  F(modbus_new_tcp_pi) \
  F(modbus_set_socket) \
  F(modbus_strerror) \
  F(modbus_tcp_pi_accept) \
  F(modbus_tcp_pi_listen)

struct s42_modbus {
#define S42_MODBUS_PTR(name) __typeof__(name) *name;
  S42_MODBUS_FNS(S42_MODBUS_PTR)
#undef S42_MODBUS_PTR
};
extern struct s42_modbus s42_modbus;

/* Load libmodbus and resolve every function above (once; then it stays):
 * 0, or -1 with a message naming the library in err. */
int s42_modbus_load(char *err, size_t n);

#ifndef S42_MODBUS_DL_IMPL
#define modbus_free (*s42_modbus.modbus_free)
#define modbus_new_tcp_pi (*s42_modbus.modbus_new_tcp_pi)
#define modbus_set_socket (*s42_modbus.modbus_set_socket)
#define modbus_strerror (*s42_modbus.modbus_strerror)
#define modbus_tcp_pi_accept (*s42_modbus.modbus_tcp_pi_accept)
#define modbus_tcp_pi_listen (*s42_modbus.modbus_tcp_pi_listen)
#endif

#endif
