#include "datafmt.h"

#include <math.h>
#include <string.h>

void json_put_str(strbuf *o, const char *s) {
    strbuf_puts(o, "\"");
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        if (*p == '"' || *p == '\\') strbuf_printf(o, "\\%c", *p);
        else if (*p == '\n') strbuf_puts(o, "\\n");
        else if (*p == '\t') strbuf_puts(o, "\\t");
        else if (*p < 0x20) strbuf_printf(o, "\\u%04x", *p);
        else strbuf_put(o, (const char *)p, 1);
    }
    strbuf_puts(o, "\"");
}

void json_put_num(strbuf *o, double v) {
    if (isnan(v)) strbuf_puts(o, "null");
    else if (isinf(v)) strbuf_puts(o, v > 0 ? "\"inf\"" : "\"-inf\"");
    else strbuf_printf(o, "%.9g", v);
}

void csv_put_str(strbuf *o, const char *s, bool quote) {
    if (!quote && !strpbrk(s, ",\"\n\r")) {
        strbuf_puts(o, s);
        return;
    }
    strbuf_puts(o, "\"");
    for (; *s; s++) strbuf_puts(o, *s == '"' ? "\"\"" : (char[2]){ *s, 0 });
    strbuf_puts(o, "\"");
}

void csv_put_num(strbuf *o, double v) {
    if (isnan(v)) return;
    if (isinf(v)) strbuf_puts(o, v > 0 ? "inf" : "-inf");
    else strbuf_printf(o, "%.9g", v);
}
