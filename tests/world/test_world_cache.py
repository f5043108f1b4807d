"""world/cache.py: what the layers above work out about a world lives in one cache the world owns (`world.cache`).

Two worlds never share an answer; a world's answers go with the world, an object's with the object; forgetting
forgets; an answer kept for a version of the world is not handed out once the world has changed.
"""
from __future__ import annotations

import gc
import weakref

import pytest

from pycram_cli import Object
from pycram_cli.reasoning import ik
from pycram_cli.reasoning.kinematics import chain_for
from pycram_cli.reasoning.visibility import _drawn_boxes
from pycram_cli.world import BulletWorld
from pycram_cli.world.cache import Memo, WorldCache, forget_everywhere


class Answer:
    """Something kept in a cache that a weak reference can watch go."""


@pytest.fixture
def two_worlds(data_dir):
    first, second = BulletWorld(), BulletWorld()
    arms = [Object("arm", "robot", data_dir / "arm.urdf", world=w) for w in (first, second)]
    yield (first, second), arms
    first.exit()
    second.exit()


def test_every_world_owns_a_cache_of_its_own(two_worlds):
    (first, second), _ = two_worlds
    assert isinstance(first.cache, WorldCache) and first.cache is not second.cache


def test_two_worlds_do_not_share_answers(two_worlds):
    (first, second), (arm_a, arm_b) = two_worlds
    chain_a = chain_for(arm_a, arm_a.get_link_id("hand"))
    assert first.cache.names() == ["kinematic chains"] and second.cache.names() == []
    chain_b = chain_for(arm_b, arm_b.get_link_id("hand"))
    assert chain_b is not chain_a and chain_for(arm_a, arm_a.get_link_id("hand")) is chain_a  # each kept in its world
    first.cache.table("answers", first)["question"] = "first"
    assert second.cache.table("answers", second) == {}


def test_two_worlds_search_the_same_ik_question_each_for_itself(two_worlds, monkeypatch):
    (first, second), arms = two_worlds
    searches = []
    search = ik.search_groups
    monkeypatch.setattr(ik, "search_groups", lambda *a, **k: searches.append(1) or search(*a, **k))
    answers = [ik.solve_link(arm, "hand", (0.4, 0.2, 0.2), joints=["shoulder", "slide"]) for arm in arms]
    assert answers[0] == answers[1] and answers[0].success and len(searches) == 2  # the second world searched too
    assert ik.ANSWERS in first.cache.names() and ik.ANSWERS in second.cache.names()
    ik.solve_link(arms[0], "hand", (0.4, 0.2, 0.2), joints=["shoulder", "slide"])
    assert len(searches) == 2  # asked again in the first world: kept there
    first.cache.forget(ik.ANSWERS)
    ik.solve_link(arms[0], "hand", (0.4, 0.2, 0.2), joints=["shoulder", "slide"])
    assert len(searches) == 3


def test_a_worlds_answers_go_with_the_world(data_dir):
    world = BulletWorld()
    arm = Object("arm", "robot", data_dir / "arm.urdf", world=world)
    answer = Answer()
    world.cache.table("answers", world)["question"] = answer
    world.cache.table("answers", arm)["question"] = answer
    gone = weakref.ref(answer)
    world.exit()
    del world, arm, answer
    gc.collect()
    assert gone() is None


def test_an_objects_answers_go_with_the_object(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj", [0.5, 0.5, 0.0])
    answer = Answer()
    world.cache.table("answers", cube)["question"] = answer
    gone = weakref.ref(answer)
    cube.remove()
    del cube, answer
    gc.collect()
    assert gone() is None


def test_forgetting_forgets_the_named_tables_the_owners_or_everything(two_worlds):
    (first, second), (arm_a, _) = two_worlds
    cache = first.cache
    cache.table("a", first)["q"] = 1
    cache.table("a", arm_a)["q"] = 2
    cache.table("b", first)["q"] = 3
    cache.forget("a", owner=arm_a)
    assert cache.table("a", first) == {"q": 1} and cache.table("a", arm_a) == {}
    cache.forget("a")
    assert cache.table("a", first) == {} and cache.table("b", first) == {"q": 3}
    cache.forget()
    assert cache.names() == []
    first.cache.table("c", first)["q"] = 4
    second.cache.table("c", second)["q"] = 5
    second.cache.table("d", second)["q"] = 6
    forget_everywhere("c")
    assert first.cache.names() == [] and second.cache.names() == ["d"]


def test_a_kept_value_is_built_again_for_a_new_stamp(world):
    builds = []

    def build():
        builds.append(world.version)
        return len(builds)

    assert world.cache.kept("k", world, world.version, build) == 1
    assert world.cache.kept("k", world, world.version, build) == 1  # the same version: kept
    world.set_gravity((0, 0, -1))
    assert world.cache.kept("k", world, world.version, build) == 2
    assert len(builds) == 2


def test_a_changed_world_does_not_get_a_stale_answer(world, data_dir):
    cube = Object("cube", "box", data_dir / "cube.obj", [0.5, 0.5, 0.0])
    _, before, _ = _drawn_boxes(cube)
    assert _drawn_boxes(cube)[1] is before  # kept while the cube's version stays
    cube.set_position([1.5, 0.5, 0.0])
    _, after, _ = _drawn_boxes(cube)
    assert after[0, :, 0] == pytest.approx(before[0, :, 0] + 1.0)


def test_a_memo_keeps_the_latest_answers_used():
    memo = Memo(2)
    memo.remember("a", 1)
    memo.remember("b", 2)
    assert memo.recall("a") == 1  # used: now the latest
    memo.remember("c", 3)
    assert (memo.recall("a"), memo.recall("b"), memo.recall("c"), len(memo)) == (1, None, 3, 2)


def test_a_table_is_one_shape(world):
    world.cache.memo("m", world, 4)
    with pytest.raises(AssertionError, match="not a plain table"):
        world.cache.table("m", world)
