# Type stubs for the octomotion package (written by hand: tests/python/test_stubs.py checks that
# every public name of the module is here and every name here is in the module).
from os import PathLike
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy
import numpy.typing as npt

__all__: List[str]

_State = Union[Sequence[float], npt.NDArray[numpy.float64]]
_Pose = Union[None, Sequence[float], npt.NDArray[numpy.float64]]

class Error(RuntimeError): ...
class FileError(Error): ...
class InvalidArgument(Error, ValueError): ...

class Reason:
    @property
    def kind(self) -> str: ...
    @property
    def link(self) -> str: ...
    @property
    def other(self) -> str: ...
    @property
    def exact(self) -> str: ...
    @property
    def margin(self) -> float: ...
    @property
    def value(self) -> float: ...
    @property
    def lower(self) -> float: ...
    @property
    def upper(self) -> float: ...
    @property
    def text(self) -> str: ...

class Scene:
    @property
    def dof(self) -> int: ...
    @property
    def joint_names(self) -> List[str]: ...
    @property
    def free_flying(self) -> bool: ...
    @property
    def checker(self) -> str: ...
    @property
    def resolution(self) -> float: ...
    @property
    def path(self) -> str: ...
    @property
    def bounds(self) -> Tuple[npt.NDArray[numpy.float64], npt.NDArray[numpy.float64]]: ...
    @property
    def object_names(self) -> List[str]: ...
    @property
    def attached_names(self) -> List[str]: ...
    def check(self, q: _State) -> bool: ...
    def check_many(
        self, Q: npt.NDArray[numpy.float64], threads: int = 1
    ) -> npt.NDArray[numpy.bool_]: ...
    def clearance(self, q: _State) -> float: ...
    def explain(self, q: _State) -> List[Reason]: ...
    def forward_kinematics(self, q: _State) -> Dict[str, npt.NDArray[numpy.float64]]: ...
    def add_object(
        self,
        name: str,
        *,
        box: Optional[Sequence[float]] = None,
        sphere: Optional[float] = None,
        cylinder: Optional[Sequence[float]] = None,
        mesh: Optional[str] = None,
        scale: Optional[Sequence[float]] = None,
        pose: _Pose = None,
    ) -> None: ...
    def remove_object(self, name: str) -> None: ...
    def move_object(self, name: str, pose: _Pose) -> None: ...
    def attach_object(
        self,
        name: str,
        link: str,
        *,
        box: Optional[Sequence[float]] = None,
        sphere: Optional[float] = None,
        cylinder: Optional[Sequence[float]] = None,
        mesh: Optional[str] = None,
        scale: Optional[Sequence[float]] = None,
        pose: _Pose = None,
        touch_links: Sequence[str] = (),
    ) -> None: ...
    def detach_object(self, name: str, leave_at: Optional[_State] = None) -> None: ...

def load_scene(
    path: Union[str, PathLike[str]],
    *,
    require_free_start_goal: bool = False,
    fit_universe_to_reach: bool = False,
    resolution: Union[None, float, str] = None,
    rounding: Optional[str] = None,
    checker: Optional[str] = None,
    planner: Optional[str] = None,
    time: Optional[float] = None,
    seed: Optional[int] = None,
    package_paths: Union[None, str, Sequence[str]] = None,
    max_surface_voxels: Optional[float] = None,
    link_resolution: Optional[float] = None,
    self_link_resolution: Optional[float] = None,
    self_pair_tables: Optional[bool] = None,
    exact_primitives: Optional[bool] = None,
) -> Scene: ...
def plan(
    scene: Scene,
    planner: str = "RRTConnect",
    time: Optional[float] = 1.0,
    seed: Optional[int] = None,
    start: Optional[_State] = None,
    goal: Optional[_State] = None,
    interpolation: float = 0.0,
) -> Optional[npt.NDArray[numpy.float64]]: ...
def trade_study(
    path: Union[str, PathLike[str]],
    *,
    states: int = 2000,
    runs: int = 0,
    fcl_octomap: bool = True,
    plan_every_setting: bool = False,
    **options: Any,
) -> Dict[str, List[Dict[str, Any]]]: ...

def bench_set(
    dir: Union[str, PathLike[str]],
    *,
    checkers: Union[str, Sequence[str]] = ("octree-fused", "fcl"),
    robot: Optional[Union[str, PathLike[str]]] = None,
    srdf: Optional[Union[str, PathLike[str]]] = None,
    fixed: Optional[Dict[str, float]] = None,
    runs: int = 1,
    limit: int = 0,
    recheck_density: float = 100,
    log_dir: Optional[Union[str, PathLike[str]]] = None,
    **overrides: Any,
) -> Dict[str, Any]: ...
