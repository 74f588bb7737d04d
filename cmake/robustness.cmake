# (filled in by the robustness work)
