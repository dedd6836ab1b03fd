// panel: the slider panel over Dear ImGui 1.86 (see panel.h). Widgets and
// layout only; every value change goes through unif.c.
#include "panel.h"
#include "strbuf.h"

#include <cfloat>
#include <climits>
#include <cstdio>
#include <cstring>
#include <new>

#include "imgui.h"
#include "imgui_internal.h"   // BringWindowToDisplayFront: the overlay stays over the panel
#include "imgui_impl_glfw.h"
#include "imgui_impl_opengl3.h"

struct panel {
    ImGuiContext *ctx;
    GLFWwindow *window;
    bool glfw_up, gl_up, in_frame;
    float display_h;            // the window height the panel was last sized to
    float width;                // the panel's width as the user left it
};

namespace {

const ImVec4 kRed(1.0f, 0.35f, 0.3f, 1.0f);
const ImVec4 kGrey(0.55f, 0.55f, 0.55f, 1.0f);

// ImGui's sliders assert on ranges wider than half the type's range.
float slider_limit(float v) {
    return v < -FLT_MAX / 2 ? -FLT_MAX / 2 : v > FLT_MAX / 2 ? FLT_MAX / 2 : v;
}
int int_limit(float v) {
    if (v < (float)(INT_MIN / 2)) return INT_MIN / 2;
    if (v > (float)(INT_MAX / 2)) return INT_MAX / 2;
    return (int)v;
}

// Hands every component the widget edited to unif.c; true when one changed.
bool apply(unif_entry *e, const float *edited, int n) {
    bool changed = false;
    for (int k = 0; k < n; k++)
        if (edited[k] != e->value[k]) changed |= unif_set_component(e, k, edited[k]);
    return changed;
}

void tooltip(const unif_entry *e) {
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    if (e->from_glib) ImGui::Text("%s:%d", e->glib_file ? e->glib_file : "(glib)", e->glib_line);
    else ImGui::TextUnformatted("from the shader (not in the glib)");
    ImGui::Text("%s%s%s", e->is_define ? "#define, " : "", unif_type_name(e->type),
                e->array_len > 1 ? " array" : "");
    if (e->widget == UNIF_WIDGET_SLIDER) ImGui::Text("range %g .. %g, default %g", e->min, e->max, e->def[0]);
    if (!e->is_define && !e->in_shader) ImGui::TextColored(kGrey, "not in the linked program");
    ImGui::EndTooltip();
}

void fixed_value_text(const unif_entry *e) {
    char text[160];
    int len = std::snprintf(text, sizeof text, "%s =", e->name);
    int shown = e->ncomp < 4 ? e->ncomp : 4;
    for (int k = 0; k < shown && len > 0 && len < (int)sizeof text; k++)
        len += std::snprintf(text + len, sizeof text - (size_t)len, " %g", e->value[k]);
    if (e->ncomp > shown && len > 0 && len < (int)sizeof text)
        std::snprintf(text + len, sizeof text - (size_t)len, " ... (%d)", e->ncomp);
    ImGui::TextColored(kGrey, "%s", text);
}

// A slider's right-click menu: a hand-in sheet of it (issue #27).
bool sheet_menu(const unif_entry *e) {
    bool picked = false;
    if (ImGui::BeginPopupContextItem("sheet")) {
        char item[160];
        std::snprintf(item, sizeof item, "Hand-in sheet: %s at 5 values, %g to %g", e->name, e->min, e->max);
        picked = ImGui::MenuItem(item);
        ImGui::EndPopup();
    }
    return picked;
}

// One entry: [reset] widget. Returns true when its value changed; *sheet
// when its right-click menu asked for a hand-in sheet of it.
bool entry_widget(unif_entry *e, bool *sheet) {
    bool changed = false;
    if (e->widget != UNIF_WIDGET_NONE) {
        bool at_default = unif_is_default(e);
        ImGui::BeginDisabled(at_default);
        if (ImGui::SmallButton("R")) { unif_reset(e); changed = !at_default; }
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("reset to the default");
        ImGui::SameLine();
    } else {
        ImGui::Dummy(ImVec2(ImGui::GetFrameHeight() * 0.75f, 0.0f));
        ImGui::SameLine();
    }
    bool absent = !e->is_define && !e->in_shader;
    if (absent) ImGui::PushStyleColor(ImGuiCol_Text, kGrey);

    float edit[UNIF_MAX_COMPONENTS];
    std::memcpy(edit, e->value, sizeof edit);
    int n = e->ncomp < 1 ? 1 : e->ncomp > UNIF_MAX_COMPONENTS ? UNIF_MAX_COMPONENTS : e->ncomp;
    const ImGuiSliderFlags clamp = ImGuiSliderFlags_AlwaysClamp;

    switch (e->widget) {
    case UNIF_WIDGET_SLIDER:
        if (unif_is_int(e)) {
            int v = int_limit(e->value[0]);
            if (ImGui::SliderInt(e->name, &v, int_limit(e->min), int_limit(e->max), "%d", clamp)) {
                edit[0] = (float)v;
                changed |= apply(e, edit, 1);
            }
        } else if (ImGui::SliderFloat(e->name, &edit[0], slider_limit(e->min), slider_limit(e->max),
                                      "%.4g", clamp)) {
            changed |= apply(e, edit, 1);
        }
        if (!e->is_define && e->min < e->max) *sheet = sheet_menu(e);
        break;
    case UNIF_WIDGET_CHECKBOX: {
        bool b = e->value[0] != 0.0f;
        if (ImGui::Checkbox(e->name, &b)) {
            edit[0] = b ? 1.0f : 0.0f;
            changed |= apply(e, edit, 1);
        }
        break;
    }
    case UNIF_WIDGET_COLOR: {
        ImGuiColorEditFlags flags = ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR;
        bool edited = n >= 4 ? ImGui::ColorEdit4(e->name, edit, flags | ImGuiColorEditFlags_AlphaBar)
                             : ImGui::ColorEdit3(e->name, edit, flags);
        if (edited) changed |= apply(e, edit, n >= 4 ? 4 : 3);
        break;
    }
    case UNIF_WIDGET_DRAG: {
        bool bounded = e->min < e->max;
        float lo = bounded ? slider_limit(e->min) : 0.0f, hi = bounded ? slider_limit(e->max) : 0.0f;
        if (ImGui::DragScalarN(e->name, ImGuiDataType_Float, edit, n, 0.01f, &lo, &hi, "%.3f",
                               bounded ? clamp : 0))
            changed |= apply(e, edit, n);
        break;
    }
    case UNIF_WIDGET_NONE:
    default:
        fixed_value_text(e);
        break;
    }
    if (absent) ImGui::PopStyleColor();
    tooltip(e);
    if (unif_type_mismatch(e)) {
        char msg[MSG_MAX];
        unif_describe_mismatch(e, msg, sizeof msg);
        ImGui::PushStyleColor(ImGuiCol_Text, kRed);
        ImGui::TextWrapped("%s", msg);
        ImGui::PopStyleColor();
    }
    return changed;
}

// Red, at the bottom of the scene area (right of scene_x) and in front of
// the panel every frame, even when the panel was clicked last: it must not
// hide the file name the message starts with.
void error_overlay(const char *text, float scene_x) {
    ImGuiIO &io = ImGui::GetIO();
    float x0 = scene_x > 0 && scene_x < io.DisplaySize.x - 100.0f ? scene_x : 0.0f;
    float w = io.DisplaySize.x - x0;
    ImGui::SetNextWindowPos(ImVec2(x0 + w * 0.5f, io.DisplaySize.y - 10.0f), ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(w - 20.0f, io.DisplaySize.y * 0.6f));
    ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.25f, 0.02f, 0.02f, 0.92f));
    ImGui::PushStyleColor(ImGuiCol_TitleBg, ImVec4(0.55f, 0.05f, 0.05f, 1.0f));
    ImGui::PushStyleColor(ImGuiCol_TitleBgActive, ImVec4(0.65f, 0.08f, 0.08f, 1.0f));
    ImGui::PushStyleColor(ImGuiCol_Border, ImVec4(0.9f, 0.2f, 0.2f, 1.0f));
    ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse |
                             ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                             ImGuiWindowFlags_NoMove;
    if (ImGui::Begin("Errors", nullptr, flags)) {
        // in front without taking the keyboard focus from a slider being typed into
        ImGui::BringWindowToDisplayFront(ImGui::GetCurrentWindow());
        ImGui::PushTextWrapPos(w - 40.0f);
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.6f, 0.55f, 1.0f));
        ImGui::TextUnformatted(text);
        ImGui::PopStyleColor();
        ImGui::PopTextWrapPos();
    }
    ImGui::End();
    ImGui::PopStyleColor(4);
}

// The panel's column at the top left, as tall as the window: sized on the
// first frame and again whenever the window's height changes (a user's drag
// of its edge holds until then).
void place_panel(panel *p) {
    ImGuiIO &io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    if (io.DisplaySize.y == p->display_h) return;
    p->display_h = io.DisplaySize.y;
    ImGui::SetNextWindowSize(ImVec2(p->width > 0 ? p->width : 420.0f,
                                    io.DisplaySize.y > 40 ? io.DisplaySize.y - 20 : 400),
                             ImGuiCond_Always);
}

// The frame budget: while the picture changes the scene is drawn smaller
// to keep a frame within it; the size it is drawn at now under it.
void budget_row(float *budget_ms, const char *resolution) {
    if (budget_ms) {
        ImGui::PushItemWidth(ImGui::GetFontSize() * 10.0f);
        ImGui::SliderFloat("Frame budget ms", budget_ms, 0.0f, 1000.0f,
                           *budget_ms > 0 ? "%.3g ms" : "off: full resolution", ImGuiSliderFlags_Logarithmic);
        ImGui::PopItemWidth();
        if (*budget_ms < 0) *budget_ms = 0;
    }
    if (resolution && resolution[0]) ImGui::TextColored(kGrey, "drawn at %s", resolution);
}

// The frame time (the window's wall time; fps from it), then the GPU's,
// which on a CPU rasteriser does not time the drawing and says so.
void timings(const panel_info *info) {
    if (info->frame_ms > 0) ImGui::Text("%.1f ms/frame  %.1f fps", info->frame_ms, info->fps);
    else ImGui::TextUnformatted("first frame");   // nothing timed yet (app.c): no fps to show
    ImGui::SameLine();
    ImGui::Text("  t = %.2f s%s", info->time_s, info->paused ? " (paused)" : "");
    if (info->gpu_ms >= 0 && info->cpu_raster)
        ImGui::TextColored(kGrey, "%.2f ms GPU: not meaningful on a CPU rasteriser", info->gpu_ms);
    else if (info->gpu_ms >= 0)
        ImGui::Text("%.2f ms GPU", info->gpu_ms);
    const char *title = info->cpu_raster ? "GPU time per pass (not meaningful here)###passes"
                                         : "GPU time per pass###passes";
    if (info->passes && info->passes[0] && ImGui::TreeNode(title)) {
        ImGui::TextUnformatted(info->passes);
        ImGui::TreePop();
    }
    budget_row(info->budget_ms, info->resolution);
}

// One collapsing header per set with a widget per entry; changes go to out.
void draw_sets(unif_set *sets, int nsets, panel_actions *out) {
    for (int s = 0; sets && s < nsets; s++) {
        unif_set *set = &sets[s];
        ImGui::PushID(s);
        char header[UNIF_NAME_MAX + 32];
        std::snprintf(header, sizeof header, "%s (%d)###set", set->program[0] ? set->program : "(unnamed)",
                      set->n);
        if (ImGui::CollapsingHeader(header, ImGuiTreeNodeFlags_DefaultOpen)) {
            bool defines_open = false;
            for (int i = 0; i < set->n; i++) {
                unif_entry *e = &set->entries[i];
                if (e->is_define && !defines_open) {
                    ImGui::TextColored(kGrey, "defines (changing one recompiles)");
                    defines_open = true;
                } else if (!e->is_define && defines_open) {
                    ImGui::Separator();
                    defines_open = false;
                }
                ImGui::PushID(i);
                bool sheet = false;
                if (entry_widget(e, &sheet) && e->is_define) out->recompile = true;
                if (sheet) {
                    out->sheet = true;
                    std::snprintf(out->sheet_program, sizeof out->sheet_program, "%s", set->program);
                    std::snprintf(out->sheet_uniform, sizeof out->sheet_uniform, "%s", e->name);
                    out->sheet_min = e->min;
                    out->sheet_max = e->max;
                }
                ImGui::PopID();
            }
            if (set->n == 0) ImGui::TextColored(kGrey, "no uniforms");
        }
        ImGui::PopID();
    }
}

}  // namespace

extern "C" {

panel *panel_create(void *glfw_window, const char *glsl_version) {
    if (!glfw_window) return nullptr;
    panel *p = new (std::nothrow) panel();
    if (!p) return nullptr;
    IMGUI_CHECKVERSION();
    p->window = static_cast<GLFWwindow *>(glfw_window);
    p->ctx = ImGui::CreateContext();
    ImGui::SetCurrentContext(p->ctx);
    ImGuiIO &io = ImGui::GetIO();
    io.IniFilename = nullptr;               // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 4.0f;
    p->glfw_up = ImGui_ImplGlfw_InitForOpenGL(p->window, true);
    p->gl_up = p->glfw_up && ImGui_ImplOpenGL3_Init(glsl_version ? glsl_version : "#version 130");
    if (!p->gl_up) {
        panel_destroy(p);
        return nullptr;
    }
    return p;
}

void panel_destroy(panel *p) {
    if (!p) return;
    ImGui::SetCurrentContext(p->ctx);
    if (p->gl_up) ImGui_ImplOpenGL3_Shutdown();
    if (p->glfw_up) ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext(p->ctx);
    delete p;
}

void panel_begin_frame(panel *p) {
    if (!p) return;
    ImGui::SetCurrentContext(p->ctx);
    if (p->in_frame) ImGui::EndFrame();     // a frame begun and never rendered
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    p->in_frame = true;
}

/* The pack drawing the world, as compare-view picks them: a new choice is
 * an action (the app reloads the scene with it); the combo shows the
 * current one until then. */
static void pack_combo(const panel_info *info, panel_actions *out) {
    if (info->npacks <= 0 || !info->packs) return;
    const char *now = info->pack >= 0 && info->pack < info->npacks ? info->packs[info->pack] : "(the scene's)";
    ImGui::PushItemWidth(ImGui::GetFontSize() * 10.0f);
    if (ImGui::BeginCombo("Pack", now)) {
        for (int i = 0; i < info->npacks; i++) {
            bool selected = i == info->pack;
            if (ImGui::Selectable(info->packs[i], selected) && !selected) {
                out->switch_pack = true;
                out->pack = i;
            }
            if (selected) ImGui::SetItemDefaultFocus();
        }
        ImGui::EndCombo();
    }
    ImGui::PopItemWidth();
}

/* Picking the row already chosen applies it again: the sliders moved since
 * go back to the setting's values. */
static void setting_combo(const panel_info *info, panel_actions *out) {
    if (info->nsettings <= 0 || !info->settings) return;
    int cur = info->setting;
    const char *now = cur >= 0 && cur < info->nsettings ? info->settings[cur] : "(choose)";
    ImGui::PushItemWidth(ImGui::GetFontSize() * 10.0f);
    if (ImGui::BeginCombo("Setting", now)) {
        for (int i = 0; i < info->nsettings; i++) {
            bool selected = i == cur;
            if (ImGui::Selectable(info->settings[i], selected)) {
                out->switch_setting = true;
                out->setting = i;
            }
            const char *tip = info->setting_tips ? info->setting_tips[i] : NULL;
            if (tip && tip[0] && ImGui::IsItemHovered()) {
                ImGui::BeginTooltip();
                ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
                ImGui::TextUnformatted(tip);
                ImGui::PopTextWrapPos();
                ImGui::EndTooltip();
            }
            if (selected) ImGui::SetItemDefaultFocus();
        }
        ImGui::EndCombo();
    }
    ImGui::PopItemWidth();
}

void panel_draw(panel *p, unif_set *sets, int nsets, const panel_info *info, panel_actions *out) {
    panel_actions none;
    if (!out) out = &none;
    std::memset(out, 0, sizeof *out);
    if (!p || !p->in_frame) return;
    ImGui::SetCurrentContext(p->ctx);

    place_panel(p);
    if (ImGui::Begin("tarn")) {
        p->width = ImGui::GetWindowWidth();
        if (info) {
            if (info->scene_path) ImGui::TextUnformatted(info->scene_path);
            timings(info);
            pack_combo(info, out);
            setting_combo(info, out);
        }
        if (ImGui::Button("Reset all")) {
            for (int s = 0; s < nsets; s++)
                if (unif_reset_all_ex(&sets[s])) out->recompile = true;
            out->reset_all = true;
        }
        ImGui::SameLine();
        out->save_preset = ImGui::Button("Save preset");
        ImGui::SameLine();
        out->load_preset = ImGui::Button("Load preset");
        ImGui::SameLine();
        out->reload = ImGui::Button("Reload");
        out->toggle_pause = ImGui::Button(info && info->paused ? "Play" : "Pause");
        ImGui::SameLine();
        out->screenshot = ImGui::Button("Screenshot");
        ImGui::Separator();

        ImGui::PushItemWidth(-ImGui::GetFontSize() * 9.0f);
        draw_sets(sets, nsets, out);
        ImGui::PopItemWidth();
    }
    ImGui::End();

    if (info && info->error_text && info->error_text[0]) error_overlay(info->error_text, info->scene_x);
}

void panel_render(panel *p) {
    if (!p) return;
    ImGui::SetCurrentContext(p->ctx);
    if (!p->in_frame) return;
    ImGui::Render();
    p->in_frame = false;
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

namespace {

// The heat maps' ramp as a bar across the panel, 0 at the left, the scale
// (and more) at the right: outside the views, so it hides none of them.
void compare_legend(const panel_compare *c) {
    ImDrawList *dl = ImGui::GetWindowDrawList();
    ImVec2 at = ImGui::GetCursorScreenPos();
    float w = ImGui::GetContentRegionAvail().x, h = ImGui::GetFontSize() * 0.8f;
    for (int i = 0; i + 1 < c->legend_n; i++) {
        const float *a = &c->legend_rgb[3 * i], *b = &c->legend_rgb[3 * (i + 1)];
        ImU32 ca = ImGui::ColorConvertFloat4ToU32(ImVec4(a[0], a[1], a[2], 1.0f));
        ImU32 cb = ImGui::ColorConvertFloat4ToU32(ImVec4(b[0], b[1], b[2], 1.0f));
        float x0 = at.x + w * i / (c->legend_n - 1), x1 = at.x + w * (i + 1) / (c->legend_n - 1);
        dl->AddRectFilledMultiColor(ImVec2(x0, at.y), ImVec2(x1, at.y + h), ca, cb, cb, ca);
    }
    ImGui::Dummy(ImVec2(w, h));
    ImGui::Text("0");
    char half[32], full[32];
    std::snprintf(half, sizeof half, "%.3g", c->legend_scale / 2);
    std::snprintf(full, sizeof full, c->legend_flip ? "%.3g" : ">= %.3g", c->legend_scale);   // FLIP ends at 1
    ImGui::SameLine(w * 0.5f - ImGui::CalcTextSize(half).x * 0.5f);
    ImGui::TextUnformatted(half);
    ImGui::SameLine(w - ImGui::CalcTextSize(full).x);
    ImGui::TextUnformatted(full);
    ImGui::TextColored(kGrey, "%s", c->legend_flip ? "HDR-FLIP (0: no visible difference)" : "error (max |RGB|), linear");
}

// Each pack's passes and their times, folded; over the views only on request.
void compare_pass_times(const panel_compare *c) {
    bool any = false;
    for (int i = 0; i < c->npacks; i++) any |= c->packs[i].passes && c->packs[i].passes[0];
    if (!any) return;
    if (!ImGui::TreeNode("pass times")) return;
    if (c->passes_over_views) ImGui::Checkbox("over the views too", c->passes_over_views);
    for (int i = 0; i < c->npacks && i < PANEL_COMPARE_MAX_PACKS; i++) {
        const panel_compare_pack *pk = &c->packs[i];
        if (!pk->passes || !pk->passes[0]) continue;
        ImGui::Text("%d %s", i + 1, pk->name);
        ImGui::Indent();
        ImGui::TextUnformatted(pk->passes);
        ImGui::Unindent();
    }
    ImGui::TreePop();
}

}  // namespace

void panel_draw_compare(panel *p, const panel_compare *c, panel_compare_actions *out) {
    panel_compare_actions none;
    if (!out) out = &none;
    std::memset(out, 0, sizeof *out);
    if (!p || !p->in_frame || !c) return;
    ImGui::SetCurrentContext(p->ctx);
    place_panel(p);
    if (ImGui::Begin("tarn compare")) {
        p->width = ImGui::GetWindowWidth();
        if (c->scene_path) ImGui::TextUnformatted(c->scene_path);
        if (c->frame_ms > 0)
            ImGui::Text("t = %.2f s%s   %.1f ms/frame  %.1f fps", c->time_s, c->paused ? " (paused)" : "",
                        c->frame_ms, c->fps);
        else ImGui::Text("t = %.2f s%s   first frame", c->time_s, c->paused ? " (paused)" : "");
        budget_row(c->budget_ms, c->resolution);
        out->common.toggle_pause = ImGui::Button(c->paused ? "Play" : "Pause");
        ImGui::SameLine();
        out->common.reload = ImGui::Button("Reload");
        ImGui::SameLine();
        out->common.screenshot = ImGui::Button("Screenshot");
        ImGui::SameLine();
        out->reset_camera = ImGui::Button("Reset camera");
        ImGui::Separator();

        if (c->layout) {
            ImGui::RadioButton("grid", c->layout, PANEL_LAYOUT_GRID);
            ImGui::SameLine();
            ImGui::RadioButton("wipe", c->layout, PANEL_LAYOUT_WIPE);
        }
        if (c->layout && *c->layout == PANEL_LAYOUT_WIPE && c->wipe_a && c->wipe_b && c->npacks > 0) {
            ImGui::PushItemWidth(ImGui::GetFontSize() * 8.0f);
            const char *names[PANEL_COMPARE_MAX_PACKS];
            char labels[PANEL_COMPARE_MAX_PACKS][80];
            int n = c->npacks < PANEL_COMPARE_MAX_PACKS ? c->npacks : PANEL_COMPARE_MAX_PACKS;
            for (int i = 0; i < n; i++) {
                std::snprintf(labels[i], sizeof labels[i], "%d %s", i + 1, c->packs[i].name);
                names[i] = labels[i];
            }
            /* a line of their own: after the radio buttons, "right" ran off the panel */
            ImGui::Combo("left", c->wipe_a, names, n);
            ImGui::SameLine();
            ImGui::Combo("right", c->wipe_b, names, n);
            ImGui::PopItemWidth();
            if (c->wipe) ImGui::SliderFloat("divider", c->wipe, 0.0f, 1.0f, "%.2f");
        }
        if (c->show_heat) ImGui::Checkbox("heat maps (H)", c->show_heat);
        ImGui::SameLine();
        out->compute_heat = ImGui::Button("Compute heat maps");
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("the CPU reference of this frame at the viewport size; time pauses");
        if (c->heat_max) {
            ImGui::PushItemWidth(ImGui::GetFontSize() * 12.0f);
            ImGui::SliderFloat("scale (0: auto)", c->heat_max, 0.0f, 1.0f, "%.3f");
            ImGui::PopItemWidth();
        }
        if (c->metric) {
            ImGui::TextUnformatted("maps:");
            ImGui::SameLine();
            ImGui::RadioButton("|RGB| error", c->metric, 0);
            ImGui::SameLine();
            ImGui::RadioButton("FLIP", c->metric, 1);
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("HDR-FLIP (Andersson et al.): what the eye sees of the difference, 0 to 1");
        }
        if (c->heat_status) ImGui::TextWrapped("%s", c->heat_status);
        if (c->legend_rgb && c->legend_n >= 2) compare_legend(c);
        ImGui::Separator();

        if (ImGui::BeginTable("timings", 5, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
            // weights of their own: measured from the contents, the columns
            // of the window's first frame (nothing measured yet) were a
            // letter wide ("1 1 natural" for "1 natural  1.20  ...")
            const ImGuiTableColumnFlags stretch = ImGuiTableColumnFlags_WidthStretch;
            ImGui::TableSetupColumn("pack", stretch, 2.4f);
            ImGui::TableSetupColumn("GPU ms", stretch, 1.0f);
            ImGui::TableSetupColumn("wall ms", stretch, 1.0f);
            ImGui::TableSetupColumn("water RMSE", stretch, 1.4f);
            ImGui::TableSetupColumn("FLIP", stretch, 0.8f);
            ImGui::TableHeadersRow();
            for (int i = 0; i < c->npacks; i++) {
                const panel_compare_pack *pk = &c->packs[i];
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::Text("%d %s", i + 1, pk->name);
                ImGui::TableNextColumn();
                if (pk->gpu_ms >= 0) ImGui::Text("%.2f", pk->gpu_ms); else ImGui::TextUnformatted("-");
                ImGui::TableNextColumn();
                if (pk->wall_ms >= 0) ImGui::Text("%.2f", pk->wall_ms); else ImGui::TextUnformatted("-");
                ImGui::TableNextColumn();
                if (pk->rmse == pk->rmse) ImGui::Text("%.4f", pk->rmse); else ImGui::TextUnformatted("-");
                ImGui::TableNextColumn();
                if (pk->flip == pk->flip) ImGui::Text("%.3f", pk->flip); else ImGui::TextUnformatted("-");
            }
            ImGui::EndTable();
        }
        compare_pass_times(c);
        if (c->note) {   // wrapped: the llvmpipe note is longer than the panel is wide
            ImGui::PushStyleColor(ImGuiCol_Text, kGrey);
            ImGui::TextWrapped("%s", c->note);
            ImGui::PopStyleColor();
        }
        ImGui::Separator();

        ImGui::PushItemWidth(-ImGui::GetFontSize() * 9.0f);
        for (int i = 0; i < c->npacks && i < PANEL_COMPARE_MAX_PACKS; i++) {
            panel_compare_pack *pk = &c->packs[i];
            ImGui::PushID(1000 + i);
            char header[160];
            std::snprintf(header, sizeof header, "%d %s###pack", i + 1, pk->name);
            if (ImGui::CollapsingHeader(header, i == 0 ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
                if (pk->error_text && pk->error_text[0]) ImGui::TextColored(kRed, "%s", pk->error_text);
                if (ImGui::SmallButton("Reset all")) {
                    for (int s = 0; s < pk->nsets; s++)
                        if (unif_reset_all_ex(&pk->sets[s])) out->recompile[i] = true;
                }
                ImGui::Indent();
                panel_actions a;
                std::memset(&a, 0, sizeof a);
                draw_sets(pk->sets, pk->nsets, &a);
                if (a.recompile) out->recompile[i] = true;
                ImGui::Unindent();
            }
            ImGui::PopID();
        }
        ImGui::PopItemWidth();
    }
    ImGui::End();
}

void panel_label(panel *p, float x, float y, const char *text, bool right_align) {
    if (!p || !p->in_frame || !text) return;
    ImGui::SetCurrentContext(p->ctx);
    ImDrawList *dl = ImGui::GetForegroundDrawList();
    ImVec2 size = ImGui::CalcTextSize(text);
    if (right_align) x -= size.x + 8;
    dl->AddRectFilled(ImVec2(x, y), ImVec2(x + size.x + 8, y + size.y + 4), IM_COL32(0, 0, 0, 170), 3.0f);
    dl->AddText(ImVec2(x + 4, y + 2), IM_COL32(255, 255, 255, 255), text);
}

void panel_label_between(panel *p, float x0, float x1, float y, const char *text) {
    if (!p || !p->in_frame || !text) return;
    ImGui::SetCurrentContext(p->ctx);
    float w = ImGui::CalcTextSize(text).x + 8;
    float x = (x0 + x1 - w) * 0.5f;
    if (x + w > x1) x = x1 - w;
    if (x < x0) x = x0;
    panel_label(p, x, y, text, false);
}

void panel_toast(panel *p, float x, float y, const char *text) {
    if (!p || !p->in_frame || !text || !text[0]) return;
    ImGui::SetCurrentContext(p->ctx);
    ImDrawList *dl = ImGui::GetForegroundDrawList();
    ImVec2 size = ImGui::CalcTextSize(text);
    float x0 = x - size.x * 0.5f - 8;
    // inside the window: a long one (a screenshot's path) centred over a
    // narrow scene area ran off its right edge
    float right = ImGui::GetIO().DisplaySize.x - 4;
    if (x0 + size.x + 16 > right) x0 = right - size.x - 16;
    if (x0 < 4) x0 = 4;
    dl->AddRectFilled(ImVec2(x0, y), ImVec2(x0 + size.x + 16, y + size.y + 10), IM_COL32(20, 70, 35, 230), 4.0f);
    dl->AddText(ImVec2(x0 + 8, y + 5), IM_COL32(255, 255, 255, 255), text);
}

bool panel_wants_mouse(const panel *p) {
    if (!p) return false;
    ImGui::SetCurrentContext(p->ctx);
    return ImGui::GetIO().WantCaptureMouse;
}

bool panel_contains(const panel *p, double x, double y) {
    if (!p) return false;
    ImGuiContext &g = *p->ctx;
    for (ImGuiWindow *w : g.Windows)   // as drawn last frame (toasts take no input)
        if (w->WasActive && !w->Hidden && !(w->Flags & ImGuiWindowFlags_NoInputs) &&
            w->Rect().Contains(ImVec2((float)x, (float)y)))
            return true;
    return false;
}

bool panel_wants_keyboard(const panel *p) {
    if (!p) return false;
    ImGui::SetCurrentContext(p->ctx);
    return ImGui::GetIO().WantCaptureKeyboard;
}

}  // extern "C"
