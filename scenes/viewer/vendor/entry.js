// What the viewer uses of three.js: update.sh bundles these (and only these) into three.min.js
// as the global THREE. A class viewer.js starts to use must be added here, then update.sh run.
export {
  Box3, BoxGeometry, BufferAttribute, BufferGeometry, Color, DirectionalLight, DoubleSide,
  DynamicDrawUsage, GridHelper, Group, HemisphereLight, InstancedMesh, LineBasicMaterial,
  LineSegments, MathUtils, Matrix4, Mesh, MeshLambertMaterial, PerspectiveCamera, PlaneGeometry,
  Points, PointsMaterial, Quaternion, Scene, SphereGeometry, Vector3, WebGLRenderer, REVISION,
} from 'three';
export { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
