"""The sweep's judge (scripts/sweep_remesh.py failures()): the Hausdorff bound where the min length
overrides epsilon, and the slack of the monotone vertex counts. Run: python3 tests/sweep/judge_test.py"""
import importlib.util
import unittest
from pathlib import Path

SPEC = importlib.util.spec_from_file_location(
    "sweep_remesh", Path(__file__).resolve().parents[2] / "scripts" / "sweep_remesh.py")
sweep = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(sweep)


def run(setting, vertices, hausdorff_pct, mesh="m.off", min_angle=30.0, feature_sector=360.0):
    return {"mesh": mesh, "setting": setting, "status": "ok", "cpu_s": 0.1, "rss_mb": 20, "note": "",
            "vertices": vertices, "hausdorff_pct": hausdorff_pct, "new_si": 0, "si_capped": False,
            "min_angle": min_angle, "feature_sector": feature_sector}


def kinds(results):
    settings = {s.name: s for s in sweep.all_settings()}
    return [(kind, r["setting"]) for kind, _, r, _ in sweep.failures(results, settings, None)]


class HausdorffBound(unittest.TestCase):
    def test_two_epsilon_where_epsilon_is_at_least_half_the_min_length(self):
        self.assertEqual(kinds([run("eps0.5-min0.2-f0", 100, 0.99)]), [])
        self.assertEqual(kinds([run("eps0.5-min0.2-f0", 100, 1.01)]), [("hausdorff", "eps0.5-min0.2-f0")])

    def test_the_min_length_where_epsilon_asks_for_shorter_edges(self):
        # eps 0.01 % at min 0.2 %: the bound is 2 x (0.2 / 2) = 0.2 %, not 0.02 %.
        self.assertEqual(kinds([run("eps0.01-min0.2-f0", 100, 0.19)]), [])
        self.assertEqual(kinds([run("eps0.01-min0.2-f0", 100, 0.21)]), [("hausdorff", "eps0.01-min0.2-f0")])
        # At min 0.02 % the same epsilon keeps (nearly) its own bound: 2 x max(0.01, 0.01) = 0.02 %.
        self.assertEqual(kinds([run("eps0.01-min0.02-f0", 100, 0.03)]), [("hausdorff", "eps0.01-min0.02-f0")])

    def test_uniform_bound_is_the_length(self):
        self.assertEqual(kinds([run("len2-f0", 100, 1.9)]), [])
        self.assertEqual(kinds([run("len2-f0", 100, 2.1)]), [("hausdorff", "len2-f0")])


class MonotoneCounts(unittest.TestCase):
    def test_noise_of_a_few_vertices_passes(self):
        # dragon after the neck fix: 5,245 at min 0.2 % against 5,224 at min 0.02 % (0.4 %).
        self.assertEqual(kinds([run("eps5-min0.02-f0", 5224, 1.0), run("eps5-min0.2-f0", 5245, 1.0)]), [])

    def test_a_coarser_setting_with_clearly_more_vertices_fails(self):
        # dragon before it: 5,246 against 2,961.
        got = kinds([run("eps5-min0.02-f0", 2961, 1.0), run("eps5-min0.2-f0", 5246, 1.0)])
        self.assertEqual(got, [("monotone", "eps5-min0.2-f0")])
        got = kinds([run("eps1-min0.2-f0", 1000, 1.0), run("eps2-min0.2-f0", 1020, 1.0)])
        self.assertEqual(got, [("monotone", "eps2-min0.2-f0")])


class MinAngle(unittest.TestCase):
    def test_twenty_degrees_where_no_feature_lines_meet(self):
        self.assertEqual(kinds([run("eps0.5-min0.2-f0", 100, 0.5, min_angle=20.5)]), [])
        self.assertEqual(kinds([run("eps0.5-min0.2-f0", 100, 0.5, min_angle=19.5)]), [("min angle", "eps0.5-min0.2-f0")])
        # Feature lines meeting at 40 degrees do not excuse anything under 20.
        self.assertEqual(kinds([run("eps0.5-min0.2-f45", 100, 0.5, min_angle=19.5, feature_sector=40)]),
                         [("min angle", "eps0.5-min0.2-f45")])

    def test_a_narrow_feature_sector_lowers_the_bound(self):
        # Two feature lines 10 degrees apart: 9 degrees (0.9 x 10) is what a remesh must reach.
        self.assertEqual(kinds([run("eps0.5-min0.2-f45", 100, 0.5, min_angle=9.5, feature_sector=10)]), [])
        self.assertEqual(kinds([run("eps0.5-min0.2-f45", 100, 0.5, min_angle=8.5, feature_sector=10)]),
                         [("min angle", "eps0.5-min0.2-f45")])


if __name__ == "__main__":
    unittest.main()
