/* The animation page of `braun plot -o FILE.html`: one self-contained file
 * — the drawing as inline SVG, one hidden group per configuration (the
 * same elements as the stroboscopic view), and a few lines of script that
 * show one group at a time, in simulated time at a chosen speed, with
 * play/pause and a time slider. It loads nothing: no script, style, font
 * or image from anywhere else, no URL at all (tests/cli/plot.sh checks). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli_plot.h"

static const char script[] =
    "(function () {\n"
    "  var f = document.getElementById('frames').children, n = f.length, T = [], k = 0;\n"
    "  var run = true, last = null, sim = 0, i;\n"
    "  for (i = 0; i < n; i++) T.push(parseFloat(f[i].getAttribute('data-t')));\n"
    /* Digits enough to tell frames apart (a 0.03 s run read "t = 0.000 s"
     * for its first 13 frames at 3). */
    "  var dig = 3;\n"
    "  for (i = 1; i < n; i++) { var g = T[i] - T[i - 1];\n"
    "    if (g > 0) dig = Math.max(dig, Math.min(12, Math.ceil(-Math.log10(g)) + 1)); }\n"
    "  var s = document.getElementById('slider'), now = document.getElementById('now');\n"
    "  var b = document.getElementById('play'), sp = document.getElementById('speed');\n"
    "  function show(j) {\n"
    "    f[k].style.display = 'none'; k = j; f[k].style.display = '';\n"
    "    s.value = j; now.textContent = 't = ' + T[j].toFixed(dig) + ' s';\n"
    "  }\n"
    "  s.oninput = function () { run = false; b.textContent = 'Play'; sim = T[+s.value]; show(+s.value); };\n"
    "  b.onclick = function () {\n"
    "    run = !run; b.textContent = run ? 'Pause' : 'Play'; last = null;\n"
    "    if (run && k === n - 1) sim = T[0];\n"
    "  };\n"
    "  function tick(ts) {\n"
    "    if (run) {\n"
    "      if (last !== null) { sim += (ts - last) / 1000 * parseFloat(sp.value); if (sim > T[n - 1]) sim = T[0]; }\n"
    "      last = ts;\n"
    "      var j = T[k] > sim ? 0 : k;\n"
    "      while (j + 1 < n && T[j + 1] <= sim) j++;\n"
    "      if (j !== k) show(j);\n"
    "    }\n"
    "    window.requestAnimationFrame(tick);\n"
    "  }\n"
    "  sim = T[0]; show(0); window.requestAnimationFrame(tick);\n"
    "})();\n";

int plot_write_html(FILE *f, const plot_job *job)
{
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>", f);
    plot_xml_text(f, job->caption);
    fputs("</title>\n<style>\nbody { font-family: sans-serif; margin: 16px; }\n"
          "#controls { margin-top: 8px; }\n#slider { width: 50%; vertical-align: middle; }\n"
          "</style>\n</head>\n<body>\n", f);
    if (job->nseries > 0 || !job->drawing) {
        /* --plot: the chart, nothing to animate. */
        int rc = plot_svg_chart(f, job, 800, 480, 1);
        fputs("</body>\n</html>\n", f);
        return rc;
    }
    const plot_drawing *dr = job->drawing;
    const plot_samples *s = job->samples;
    plot_canvas cv;
    plot_canvas_fit(&cv, job);
    double *pos = malloc((size_t)dr->nanchors * 3 * sizeof *pos);
    braun_real *qr = malloc((size_t)s->n * sizeof *qr);
    if (!pos || !qr) {
        free(pos);
        free(qr);
        braun_cli_error("out of memory");
        return -1;
    }
    const long frames = job->frames < s->count ? job->frames : s->count;
    plot_svg_header(f, cv.width, cv.height, job->caption, 1);
    plot_drawing_eval(dr, s->rows + 1, qr, pos);
    plot_svg_items(f, job, &cv, pos, s->rows[0], PLOT_LAYER_UNDER, "  ");
    plot_svg_paths(f, job, &cv, "stroke-width=\"1.2\" stroke-opacity=\"0.45\"");
    fputs("  <g id=\"frames\">\n", f);
    for (long k = 0; k < frames; k++) {
        const long r = plot_frame_row(job, k);
        const double *row = s->rows + (size_t)r * (size_t)s->cols;
        char t[BRAUN_CLI_NUMBER_SIZE];
        plot_drawing_eval(dr, row + 1, qr, pos);
        fprintf(f, "  <g data-t=\"%s\" style=\"display:none\">\n", braun_cli_number(row[0], t));
        plot_svg_items(f, job, &cv, pos, row[0], PLOT_LAYER_ALL_MOVING, "    ");
        for (int i = 0; i < dr->ntraces; i++) {
            double x, y;
            plot_canvas_xy(&cv, dr, pos + 3 * dr->traces[i].anchor, &x, &y);
            fprintf(f, "    <circle cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"%s\"/>\n", x, y,
                    plot_colour(i));
        }
        fputs("  </g>\n", f);
    }
    fputs("  </g>\n", f);
    plot_drawing_eval(dr, s->rows + 1, qr, pos);
    plot_svg_items(f, job, &cv, pos, s->rows[0], PLOT_LAYER_MARKS, "  ");
    plot_svg_caption(f, job, &cv);
    plot_svg_scale_bar(f, &cv);
    fputs("</svg>\n", f);
    fprintf(f, "<div id=\"controls\">\n<button id=\"play\" type=\"button\">Pause</button>\n"
               "<input id=\"slider\" type=\"range\" min=\"0\" max=\"%ld\" value=\"0\" step=\"1\">\n"
               "<span id=\"now\"></span>\n<label>speed <select id=\"speed\">\n",
            frames > 0 ? frames - 1 : 0);
    static const char *const speeds[] = {"0.1", "0.25", "0.5", "1", "2", "5", "10", "100"};
    for (size_t i = 0; i < sizeof speeds / sizeof speeds[0]; i++)
        fprintf(f, "<option value=\"%s\"%s>%s&#215;</option>\n", speeds[i],
                speeds[i][0] == '1' && speeds[i][1] == '\0' ? " selected" : "", speeds[i]);
    fputs("</select></label>\n</div>\n<script>\n", f);
    fputs(script, f);
    fputs("</script>\n</body>\n</html>\n", f);
    free(pos);
    free(qr);
    return 0;
}
