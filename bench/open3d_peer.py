#!/usr/bin/python3
"""The peer glint is compared with (issue 13): Open3D's point-to-plane ICP of the examined
mesh's vertices onto the reference (vertices with their normals), then the signed
closest-point distance of every reference vertex to the fitted examined surface, the work a
C2M user does with Open3D. Run by bench/peers_bench.cpp with Debian's python3-open3d:

    /usr/bin/python3 bench/open3d_peer.py REFERENCE.ply EXAMINED.ply [--one-scale]

By default the ICP runs coarse to fine, converged: a gate of 5 % of the reference's bounding
diagonal, then 1 %, each to relative changes of 1e-9 or 100 iterations: what a user who wants
glint's registration accuracy runs. --one-scale runs Open3D's defaults once (5 % gate, 30
iterations, relative changes of 1e-6): about 6x less accurate on the bench pair.

Prints one JSON object: seconds per step (import, load, icp, distance; `work` = load + icp +
distance, what the process did after importing Open3D), the fit (reference_from_examined, a
4×4 list of rows) and the ICP's own evidence.
"""
import json
import sys
import time

t0 = time.perf_counter()
import numpy as np  # noqa: E402
import open3d as o3d  # noqa: E402

# note: the first correspondence gate, 5 % of the reference's bounding diagonal, holds the
# bench pair's initial misalignment (5° and 2 % of the size move a point by at most ~1.5 mm on
# a 31 mm diagonal), as an Open3D user would set it; 30 iterations and the relative changes of
# 1e-6 are Open3D's defaults (--one-scale).
GATES = (0.05, 0.01)


def main():
    reference_path, examined_path = sys.argv[1], sys.argv[2]
    one_scale = "--one-scale" in sys.argv[3:]
    t_import = time.perf_counter()
    reference = o3d.io.read_triangle_mesh(reference_path)
    examined = o3d.io.read_triangle_mesh(examined_path)
    if not reference.has_vertex_normals():
        reference.compute_vertex_normals()
    target = o3d.geometry.PointCloud(reference.vertices)
    target.normals = reference.vertex_normals
    source = o3d.geometry.PointCloud(examined.vertices)
    t_load = time.perf_counter()

    diagonal = np.linalg.norm(reference.get_max_bound() - reference.get_min_bound())
    registration = o3d.pipelines.registration
    if one_scale:
        steps = [(GATES[0], registration.ICPConvergenceCriteria())]
    else:
        converged = registration.ICPConvergenceCriteria(
            relative_fitness=1e-9, relative_rmse=1e-9, max_iteration=100)
        steps = [(gate, converged) for gate in GATES]
    pose = np.eye(4)
    for gate, criteria in steps:
        fit = registration.registration_icp(
            source, target, gate * diagonal, pose,
            registration.TransformationEstimationPointToPlane(), criteria)
        pose = fit.transformation
    t_icp = time.perf_counter()

    examined.transform(fit.transformation)
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.t.geometry.TriangleMesh.from_legacy(examined))
    points = o3d.core.Tensor(np.asarray(reference.vertices, dtype=np.float32))
    distance = scene.compute_signed_distance(points).numpy()
    t_distance = time.perf_counter()

    print(json.dumps({
        "open3d": o3d.__version__,
        "configuration": "one scale (defaults)" if one_scale else "coarse to fine, converged",
        "import_s": t_import - t0,
        "load_s": t_load - t_import,
        "icp_s": t_icp - t_load,
        "distance_s": t_distance - t_icp,
        "work_s": t_distance - t_import,
        "reference_from_examined": np.asarray(fit.transformation).tolist(),
        "fitness": fit.fitness,
        "inlier_rmse": fit.inlier_rmse,
        "vertices": int(distance.shape[0]),
        "max_abs_distance": float(np.max(np.abs(distance))),
    }))


if __name__ == "__main__":
    main()
