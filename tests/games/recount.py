"""The independent recount of tests/games/recount.h in Python, from a libpool-result/1 document's
events (docs/games.md "What the rules read"): the oracle of the command and binding tests."""

import math


def struck(result):
    ev = result["events"][0]
    assert ev["type"] == "strike"
    return ev["balls"][0], ev["after"][0]["pos"][2]  # the struck ball and R (z on the cloth)


def touches(ev, cue, radius):
    """The balls the struck ball touches in one event, nearest first."""
    if cue not in ev["balls"]:
        return []
    if ev["type"] == "ball_ball":
        return [b for b in ev["balls"] if b != cue][:1]
    if ev["type"] not in ("link_begin", "link_step"):
        return []
    me = next(a for a in ev["after"] if a["id"] == cue)["pos"]
    near = []
    for a in ev["after"]:
        if a["id"] == cue:
            continue
        d = math.dist(a["pos"], me)
        if d <= 2 * radius + 1e-6:
            near.append((d, a["id"]))
    return [b for _, b in sorted(near)]


def recount(result):
    """first_hit (None), rails_after_contact, pocketed, pockets, off_table, the second ball the
    struck ball meets and its cushions before it, object balls with a cushion event."""
    cue, radius = struck(result)
    first = second = None
    first_at = None
    cushions = 0
    for k, ev in enumerate(result["events"][1:], start=1):
        if ev["type"] == "ball_cushion" and ev["balls"][0] == cue and second is None:
            cushions += 1
        for b in touches(ev, cue, radius):
            if first is None:
                first, first_at = b, k
            elif second is None and b != first:
                second = b
    rails = 0 if first_at is None else sum(1 for ev in result["events"][first_at + 1:]
                                           if ev["type"] == "ball_cushion")
    pocketed = [ev["balls"][0] for ev in result["events"] if ev["type"] == "pocket"]
    pockets = [ev["pocket"] for ev in result["events"] if ev["type"] == "pocket"]
    off = [ev["balls"][0] for ev in result["events"] if ev["type"] == "off_table"]
    railed = {ev["balls"][0] for ev in result["events"] if ev["type"] == "ball_cushion"}
    return {"first_hit": first, "rails_after_contact": rails, "pocketed": pocketed, "pockets": pockets,
            "off_table": off, "second_hit": second, "cue_cushions": cushions, "railed": railed}
