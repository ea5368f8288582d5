/* The scenes of the built-in models that have one (data/slider-crank.json,
 * data/four-bar.json, data/pendulum.json, the same coordinates: see
 * tests/test_scene_paper.c), built into the tool so that a built-in model's
 * CSV columns carry names and `braun plot` can draw it from any directory.
 * tests/cli/plot.sh checks that a built-in model and its data/ file give
 * the same CSV header and the same drawing. */
#include <string.h>

#include "braun_cli.h"

static const char slider_crank_json[] =
    "{\n"
    "  \"name\": \"slider-crank\",\n"
    "  \"description\": \"slider-crank of Sec. 4.1 (Fig. 1): two rigid links l = 1 m, m = 1 kg; reproduces the built-in model\",\n"
    "  \"bodies\": [\n"
    "    {\"name\": \"crank\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": 0.083333333333333329,\n"
    "     \"position\": [0.35355339059327379, 0.35355339059327379], \"angle\": 0.78539816339744828,\n"
    "     \"points\": {\"O\": [-0.5, 0], \"A\": [0.5, 0]}},\n"
    "    {\"name\": \"rod\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": 0.083333333333333329,\n"
    "     \"position\": [1.0606601717798214, 0.35355339059327379], \"angle\": -0.78539816339744828,\n"
    "     \"points\": {\"A\": [-0.5, 0], \"B\": [0.5, 0]}}\n"
    "  ],\n"
    "  \"joints\": [\n"
    "    {\"name\": \"pivot\", \"type\": \"revolute\", \"a\": \"crank.O\", \"b\": [0, 0]},\n"
    "    {\"name\": \"knee\", \"type\": \"revolute\", \"a\": \"crank.A\", \"b\": \"rod.A\"},\n"
    "    {\"name\": \"slide\", \"type\": \"slider\", \"point\": \"rod.B\", \"line\": [0, 0], \"axis\": [1, 0]}\n"
    "  ],\n"
    "  \"effects\": [\n"
    "    {\"type\": \"gravity\", \"g\": [0, -9.81]}\n"
    "  ],\n"
    "  \"corrections\": [\"position\", \"velocity\", \"energy\"],\n"
    "  \"reference\": \"slider-crank\"\n"
    "}\n"
    ;

static const char four_bar_json[] =
    "{\n"
    "  \"name\": \"four-bar\",\n"
    "  \"description\": \"double four-bar linkage of Sec. 4.2 (Fig. 5): five uniform rods l = 1 m, m = 1 kg in natural coordinates; reproduces the built-in model\",\n"
    "  \"bodies\": [\n"
    "    {\"name\": \"J1\", \"type\": \"particle\", \"mass\": 0, \"position\": [0, 1], \"velocity\": [1, 0]},\n"
    "    {\"name\": \"J2\", \"type\": \"particle\", \"mass\": 0, \"position\": [1, 1], \"velocity\": [1, 0]},\n"
    "    {\"name\": \"J3\", \"type\": \"particle\", \"mass\": 0, \"position\": [2, 1], \"velocity\": [1, 0]}\n"
    "  ],\n"
    "  \"rods\": [\n"
    "    {\"name\": \"crank1\", \"a\": [0, 0], \"b\": \"J1\", \"mass\": 1, \"length\": 1},\n"
    "    {\"name\": \"crank2\", \"a\": [1, 0], \"b\": \"J2\", \"mass\": 1, \"length\": 1},\n"
    "    {\"name\": \"crank3\", \"a\": [2, 0], \"b\": \"J3\", \"mass\": 1, \"length\": 1},\n"
    "    {\"name\": \"coupler12\", \"a\": \"J1\", \"b\": \"J2\", \"mass\": 1, \"length\": 1},\n"
    "    {\"name\": \"coupler23\", \"a\": \"J2\", \"b\": \"J3\", \"mass\": 1, \"length\": 1}\n"
    "  ],\n"
    "  \"effects\": [\n"
    "    {\"type\": \"gravity\", \"g\": [0, -9.81]}\n"
    "  ],\n"
    "  \"reference\": \"four-bar\"\n"
    "}\n"
    ;

static const char pendulum_json[] =
    "{\n"
    "  \"name\": \"pendulum\",\n"
    "  \"description\": \"point mass 1 kg on a massless rod of 1 m, released from the horizontal; reproduces the built-in model\",\n"
    "  \"bodies\": [\n"
    "    {\"name\": \"bob\", \"type\": \"particle\", \"mass\": 1, \"position\": [1, 0]}\n"
    "  ],\n"
    "  \"joints\": [\n"
    "    {\"name\": \"rod\", \"type\": \"distance\", \"a\": [0, 0], \"b\": \"bob\", \"length\": 1}\n"
    "  ],\n"
    "  \"effects\": [\n"
    "    {\"type\": \"gravity\", \"g\": [0, -9.81]}\n"
    "  ],\n"
    "  \"reference\": \"pendulum\"\n"
    "}\n"
    ;

static const struct {
    const char *name, *text;
} scenes[] = {
    {"slider-crank", slider_crank_json},
    {"four-bar", four_bar_json},
    {"pendulum", pendulum_json},
};

const char *braun_cli_builtin_scene(const char *name)
{
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++)
        if (strcmp(scenes[i].name, name) == 0) return scenes[i].text;
    return NULL;
}
