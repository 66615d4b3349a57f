"""A simulated drive base as a native ROS 2 (rclpy) node, for Docent's rosbridge tests.

It drives in a straight line toward the last goal on the goal topic (geometry_msgs/PoseStamped,
as Nav2's bt_navigator takes `/goal_pose`) at a set speed, publishes its pose on the pose topic
at a set rate whether it moves or not (geometry_msgs/PoseWithCovarianceStamped like AMCL's
`/amcl_pose`, or nav_msgs/Odometry like `/odom`), and halts on a std_msgs/Empty on the stop
topic or a zero geometry_msgs/Twist on the velocity topic. Each goal and stop it takes is
published on `/sim/log` (std_msgs/String, JSON) so a test can see what reached the robot.

Run through tests/ros/run.sh with the test's own ROS_DOMAIN_ID.
"""

import argparse
import json
import math

import rclpy
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped, Twist
from nav_msgs.msg import Odometry
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import Empty, String


def parse_args():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--goal-topic", default="/goal_pose")
    p.add_argument("--pose-topic", default="/amcl_pose")
    p.add_argument("--pose-type", choices=["amcl", "odom"], default="amcl")
    p.add_argument("--stop-topic", default="/docent/stop")
    p.add_argument("--cmd-vel", default="/cmd_vel")
    p.add_argument("--speed", type=float, default=1.0, help="metres per second")
    p.add_argument("--rate", type=float, default=20.0, help="pose messages per second")
    return p.parse_args()


class SimBase(Node):
    def __init__(self, args):
        super().__init__("docent_sim_base")
        self.args = args
        self.x = self.y = self.yaw = 0.0
        self.goal = None
        kind = PoseWithCovarianceStamped if args.pose_type == "amcl" else Odometry
        self.pose_pub = self.create_publisher(kind, args.pose_topic, 10)
        self.log_pub = self.create_publisher(String, "/sim/log", 10)
        self.create_subscription(PoseStamped, args.goal_topic, self.on_goal, 10)
        self.create_subscription(Empty, args.stop_topic, lambda _m: self.halt("stop"), 10)
        self.create_subscription(Twist, args.cmd_vel, self.on_twist, 10)
        self.create_timer(1.0 / args.rate, self.tick)
        # A heartbeat on the log: a test's fresh subscription waits for one before it acts, so
        # that DDS has matched it with this publisher and no entry it awaits can be lost.
        self.create_timer(0.05, lambda: self.log(alive=True))

    def log(self, **entry):
        self.log_pub.publish(String(data=json.dumps(entry)))

    def on_goal(self, msg):
        p = msg.pose.position
        self.goal = (p.x, p.y)
        self.log(goal=[p.x, p.y], frame=msg.header.frame_id)

    def on_twist(self, msg):
        if msg.linear.x == 0.0 and msg.linear.y == 0.0 and msg.angular.z == 0.0:
            self.halt("cmd_vel")

    def halt(self, by):
        self.goal = None
        self.log(stop=by, at=[self.x, self.y])

    def tick(self):
        if self.goal is not None:
            dx, dy = self.goal[0] - self.x, self.goal[1] - self.y
            distance = math.hypot(dx, dy)
            step = self.args.speed / self.args.rate
            if distance <= step:
                self.x, self.y = self.goal
                self.goal = None
            else:
                self.yaw = math.atan2(dy, dx)
                self.x += dx / distance * step
                self.y += dy / distance * step
        self.publish_pose()

    def publish_pose(self):
        if self.args.pose_type == "amcl":
            msg = PoseWithCovarianceStamped()
            pose = msg.pose.pose
        else:
            msg = Odometry()
            msg.child_frame_id = "base_link"
            pose = msg.pose.pose
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.header.frame_id = "map" if self.args.pose_type == "amcl" else "odom"
        pose.position.x, pose.position.y = self.x, self.y
        pose.orientation.z = math.sin(self.yaw / 2)
        pose.orientation.w = math.cos(self.yaw / 2)
        self.pose_pub.publish(msg)


def main():
    args = parse_args()
    rclpy.init()
    node = SimBase(args)
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass


if __name__ == "__main__":
    main()
