/* UTF-8 (src/core/utf8.h). */
#include "utf8.h"

int32_t utf8_decode(const unsigned char *s, size_t left, size_t *len)
{
  unsigned char b = s[0];
  *len = 1;
  if (b < 0x80)
    return b;
  int need;
  int32_t c;
  if ((b & 0xE0) == 0xC0) { need = 1; c = b & 0x1F; }
  else if ((b & 0xF0) == 0xE0) { need = 2; c = b & 0x0F; }
  else if ((b & 0xF8) == 0xF0) { need = 3; c = b & 0x07; }
  else return UTF8_BAD;
  if ((size_t)need >= left)
    return UTF8_BAD;
  for (int i = 1; i <= need; i++) {
    if ((s[i] & 0xC0) != 0x80)
      return UTF8_BAD;
    c = (c << 6) | (s[i] & 0x3F);
  }
  if ((need == 1 && c < 0x80) || (need == 2 && c < 0x800) || (need == 3 && c < 0x10000) || c > 0x10FFFF ||
      (c >= 0xD800 && c <= 0xDFFF))
    return UTF8_BAD;
  *len = (size_t)need + 1;
  return c;
}
int utf8_encode(int32_t c, char *buf)
{
  if (c < 0x80) { buf[0] = (char)c; return 1; }
  if (c < 0x800) { buf[0] = (char)(0xC0 | (c >> 6)); buf[1] = (char)(0x80 | (c & 0x3F)); return 2; }
  if (c < 0x10000) {
    buf[0] = (char)(0xE0 | (c >> 12)); buf[1] = (char)(0x80 | ((c >> 6) & 0x3F));
    buf[2] = (char)(0x80 | (c & 0x3F)); return 3;
  }
  buf[0] = (char)(0xF0 | (c >> 18)); buf[1] = (char)(0x80 | ((c >> 12) & 0x3F));
  buf[2] = (char)(0x80 | ((c >> 6) & 0x3F)); buf[3] = (char)(0x80 | (c & 0x3F));
  return 4;
}

int utf8_latin_lookalike(int32_t c)
{
  switch (c) {
  case 0x0410: return 'A';
  case 0x0412: return 'B';
  case 0x0421: return 'C';
  case 0x0415: return 'E';
  case 0x041D: return 'H';
  case 0x041A: return 'K';
  case 0x041C: return 'M';
  case 0x041E: return 'O';
  case 0x0420: return 'P';
  case 0x0422: return 'T';
  case 0x0425: return 'X';
  default: return 0;
  }
}
